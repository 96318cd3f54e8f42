; expect 3:18 :teleportation
(define (domain d)
  (:requirements :teleportation :strips)
  (:predicates (p ?x)))
