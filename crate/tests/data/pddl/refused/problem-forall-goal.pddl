; expect 6:11 forall
(define (problem pr)
  (:domain base)
  (:objects o)
  (:init (p o))
  (:goal (forall (?x) (p ?x))))
