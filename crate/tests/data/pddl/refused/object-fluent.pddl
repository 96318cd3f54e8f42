; expect 4:28 place
(define (domain d)
  (:predicates (q))
  (:functions (where ?x) - place))
