; r3 has no door: the goal is unreachable in the delete relaxation.
(define (problem rooms-unreachable)
  (:domain rooms)
  (:objects r1 r2 r3 - room k1 k2 - key)
  (:init (at hall) (door hall r1) (door r1 r2) (locked r2) (key-at k1 r1) (opens k1 r2))
  (:goal (and (at r3))))
