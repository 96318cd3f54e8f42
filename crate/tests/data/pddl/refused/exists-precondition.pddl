; expect 5:20 exists
(define (domain d)
  (:predicates (p ?x) (q))
  (:action a :parameters ()
    :precondition (exists (?x) (p ?x))
    :effect (not (q))))
