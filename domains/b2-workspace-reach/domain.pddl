; B2 Workspace Reach (Logic-LfD, RA-L 2024, section IV-A-2).
; One arm, blocks partly out of reach, an L-shaped hook that pulls them in, a shelf.
; No stack/unstack, as in the paper.
(define (domain b2-workspace-reach)
  (:requirements :strips :typing :negative-preconditions)
  (:types arm graspable - object block hook - graspable)
  (:predicates
    (ontable ?x - graspable)
    (onshelf ?x - block)
    (holding ?r - arm ?x - graspable)
    (handempty ?r - arm)
    (inreach ?r - arm ?x - graspable))

  (:action pick
    :parameters (?r - arm ?x - graspable)
    :precondition (and (handempty ?r) (ontable ?x) (inreach ?r ?x))
    :effect (and (holding ?r ?x) (not (handempty ?r)) (not (ontable ?x))))

  (:action place
    :parameters (?r - arm ?x - graspable)
    :precondition (holding ?r ?x)
    :effect (and (ontable ?x) (handempty ?r) (not (holding ?r ?x))))

  (:action place-on-shelf
    :parameters (?r - arm ?x - block)
    :precondition (holding ?r ?x)
    :effect (and (onshelf ?x) (handempty ?r) (not (holding ?r ?x))))

  (:action pull
    :parameters (?r - arm ?h - hook ?x - block)
    :precondition (and (holding ?r ?h) (ontable ?x) (not (inreach ?r ?x)))
    :effect (inreach ?r ?x)))
