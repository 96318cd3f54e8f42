; expect 6:19 when
(define (domain d)
  (:predicates (p ?x) (q))
  (:action a :parameters (?x)
    :precondition (p ?x)
    :effect (and (when (q) (not (p ?x))))))
