; expect 6:4 :length
(define (problem pr)
  (:domain base)
  (:objects o)
  (:init (p o))
  (:length (:serial 4))
  (:goal (q)))
