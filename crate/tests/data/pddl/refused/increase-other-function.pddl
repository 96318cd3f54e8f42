; expect 6:29 increase
(define (domain d)
  (:predicates (q))
  (:functions (total-cost) - number (fuel) - number)
  (:action a :parameters ()
    :effect (and (not (q)) (increase (fuel) 1))))
