; expect 5:14 forall
(define (domain d)
  (:predicates (p ?x) (q))
  (:action a :parameters ()
    :effect (forall (?x) (not (p ?x)))))
