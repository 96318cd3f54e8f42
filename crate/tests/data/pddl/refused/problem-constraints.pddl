; expect 6:4 :constraints
(define (problem pr)
  (:domain base)
  (:objects o)
  (:init (p o))
  (:constraints (sometime (q)))
  (:goal (q)))
