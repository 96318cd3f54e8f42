; expect 4:4 :derived
(define (domain d)
  (:predicates (p ?x) (q ?x))
  (:derived (q ?x) (p ?x)))
