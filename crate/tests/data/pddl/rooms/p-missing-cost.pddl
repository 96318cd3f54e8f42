; The metric asks for costs but (dist r1 r2) has no value.
(define (problem rooms-missing-cost)
  (:domain rooms)
  (:objects r1 r2 - room k1 - key)
  (:init (at hall) (door hall r1) (door r1 r2)
         (= (dist hall r1) 3) (= (dist r1 hall) 3))
  (:goal (at r2))
  (:metric minimize (total-cost)))
