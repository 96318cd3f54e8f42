; expect 4:4 :durative-action
(define (domain d)
  (:predicates (q))
  (:durative-action a :parameters () :duration (= ?duration 1)
    :condition (at start (q)) :effect (at end (not (q)))))
