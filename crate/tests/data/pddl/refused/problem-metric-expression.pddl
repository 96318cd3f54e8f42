; expect 7:22 +
(define (problem pr)
  (:domain base)
  (:objects o)
  (:init (p o))
  (:goal (q))
  (:metric minimize (+ (total-cost) 1)))
