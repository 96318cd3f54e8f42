; expect 3:26 :adl
(define (domain d)
  (:requirements :strips :adl)
  (:predicates (p ?x)))
