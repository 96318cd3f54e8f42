; expect 5:25 either
(define (domain d)
  (:requirements :typing)
  (:types a b)
  (:predicates (p ?x - (either a b))))
