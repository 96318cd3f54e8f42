; B3 Dual-arm Block Transportation (Logic-LfD, RA-L 2024, section IV-A-3).
; Blocks world with two arms and table regions: an arm can only act in the regions it reaches
; (static facts), so blocks travel from the left table to the right table through the hand-over
; region that both arms reach.
(define (domain b3-dual-arm)
  (:requirements :strips :typing)
  (:types arm block region)
  (:predicates
    (on ?x - block ?y - block)
    (ontable ?x - block)
    (clear ?x - block)
    (holding ?r - arm ?x - block)
    (handempty ?r - arm)
    (at ?x - block ?p - region)
    (reaches ?r - arm ?p - region))

  (:action pick
    :parameters (?r - arm ?x - block ?p - region)
    :precondition (and (handempty ?r) (clear ?x) (ontable ?x) (at ?x ?p) (reaches ?r ?p))
    :effect (and (holding ?r ?x) (not (handempty ?r)) (not (clear ?x)) (not (ontable ?x))
                 (not (at ?x ?p))))

  (:action place
    :parameters (?r - arm ?x - block ?p - region)
    :precondition (and (holding ?r ?x) (reaches ?r ?p))
    :effect (and (ontable ?x) (at ?x ?p) (clear ?x) (handempty ?r) (not (holding ?r ?x))))

  (:action stack
    :parameters (?r - arm ?x - block ?y - block ?p - region)
    :precondition (and (holding ?r ?x) (clear ?y) (at ?y ?p) (reaches ?r ?p))
    :effect (and (on ?x ?y) (at ?x ?p) (clear ?x) (handempty ?r) (not (holding ?r ?x))
                 (not (clear ?y))))

  (:action unstack
    :parameters (?r - arm ?x - block ?y - block ?p - region)
    :precondition (and (handempty ?r) (on ?x ?y) (clear ?x) (at ?x ?p) (reaches ?r ?p))
    :effect (and (holding ?r ?x) (clear ?y) (not (on ?x ?y)) (not (clear ?x))
                 (not (handempty ?r)) (not (at ?x ?p)))))
