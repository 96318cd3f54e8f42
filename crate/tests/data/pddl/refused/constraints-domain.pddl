; expect 4:4 :constraints
(define (domain d)
  (:predicates (p ?x))
  (:constraints (always (p a))))
