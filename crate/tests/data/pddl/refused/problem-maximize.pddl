; expect 7:12 maximize
(define (problem pr)
  (:domain base)
  (:objects o)
  (:init (p o))
  (:goal (q))
  (:metric maximize (total-cost)))
