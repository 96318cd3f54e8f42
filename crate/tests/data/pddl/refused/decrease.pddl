; expect 6:29 decrease
(define (domain d)
  (:predicates (q))
  (:functions (total-cost) - number (fuel) - number)
  (:action a :parameters ()
    :effect (and (not (q)) (decrease (fuel) 1))))
