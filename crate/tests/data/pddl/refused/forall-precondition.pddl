; expect 5:29 forall
(define (domain d)
  (:predicates (p ?x) (q))
  (:action a :parameters ()
    :precondition (and (q) (forall (?x) (p ?x)))
    :effect (not (q))))
