; expect 5:20 imply
(define (domain d)
  (:predicates (p ?x) (q))
  (:action a :parameters (?x)
    :precondition (imply (q) (p ?x))
    :effect (not (q))))
