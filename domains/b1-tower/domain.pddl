; B1 Tower Construction (Logic-LfD, RA-L 2024, section IV-A-1).
; Four-operator blocks world with an explicit arm parameter so every benchmark reads alike.
(define (domain b1-tower)
  (:requirements :strips :typing)
  (:types arm block)
  (:predicates
    (on ?x - block ?y - block)
    (ontable ?x - block)
    (clear ?x - block)
    (holding ?r - arm ?x - block)
    (handempty ?r - arm))

  (:action pick
    :parameters (?r - arm ?x - block)
    :precondition (and (handempty ?r) (clear ?x) (ontable ?x))
    :effect (and (holding ?r ?x) (not (handempty ?r)) (not (clear ?x)) (not (ontable ?x))))

  (:action place
    :parameters (?r - arm ?x - block)
    :precondition (holding ?r ?x)
    :effect (and (ontable ?x) (clear ?x) (handempty ?r) (not (holding ?r ?x))))

  (:action stack
    :parameters (?r - arm ?x - block ?y - block)
    :precondition (and (holding ?r ?x) (clear ?y))
    :effect (and (on ?x ?y) (clear ?x) (handempty ?r) (not (holding ?r ?x)) (not (clear ?y))))

  (:action unstack
    :parameters (?r - arm ?x - block ?y - block)
    :precondition (and (handempty ?r) (on ?x ?y) (clear ?x))
    :effect (and (holding ?r ?x) (clear ?y) (not (on ?x ?y)) (not (clear ?x)) (not (handempty ?r)))))
