; expect 5:44 <
(define (domain d)
  (:predicates (q))
  (:functions (fuel) - number)
  (:action a :parameters () :precondition (< (fuel) 3)
    :effect (not (q))))
