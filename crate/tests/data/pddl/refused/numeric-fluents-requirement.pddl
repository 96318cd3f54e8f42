; expect 3:18 :numeric-fluents
(define (domain d)
  (:requirements :numeric-fluents)
  (:predicates (p ?x)))
