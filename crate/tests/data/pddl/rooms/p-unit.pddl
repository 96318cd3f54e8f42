; No metric: every action costs 1. An or-goal with two reachable alternatives and a negative goal.
(define (problem rooms-unit)
  (:domain rooms)
  (:objects r1 r2 r3 - room k1 k2 - key)
  (:init (at hall) (door hall r1) (door r1 r2) (door r2 r2) (locked r2)
         (key-at k1 r1) (key-at k2 r3) (opens k1 r2))
  (:goal (or (and (at r2) (not (locked r2))) (and (has k1) (not (at hall)) (= r1 r1)))))
