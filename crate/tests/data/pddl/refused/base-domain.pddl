; A valid domain the problem-level refusal files are parsed against.
(define (domain base)
  (:requirements :strips :action-costs)
  (:predicates (p ?x) (q))
  (:functions (total-cost) - number)
  (:action a :parameters (?x) :precondition (p ?x) :effect (and (q) (increase (total-cost) 1))))
