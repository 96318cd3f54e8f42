; Shelf tower: one arm builds a tower in a given order on a small shelf. The shelf holds one
; block's footprint, so a block already standing on it must go to the table first.
(define (domain shelf-tower)
  (:requirements :strips :typing)
  (:types arm block)
  (:predicates
    (on ?x - block ?y - block)
    (ontable ?x - block)
    (onshelf ?x - block)
    (clear ?x - block)
    (holding ?r - arm ?x - block)
    (handempty ?r - arm))

  (:action pick
    :parameters (?r - arm ?x - block)
    :precondition (and (handempty ?r) (clear ?x) (ontable ?x))
    :effect (and (holding ?r ?x) (not (handempty ?r)) (not (clear ?x)) (not (ontable ?x))))

  (:action take-from-shelf
    :parameters (?r - arm ?x - block)
    :precondition (and (handempty ?r) (clear ?x) (onshelf ?x))
    :effect (and (holding ?r ?x) (not (handempty ?r)) (not (clear ?x)) (not (onshelf ?x))))

  (:action unstack
    :parameters (?r - arm ?x - block ?y - block)
    :precondition (and (handempty ?r) (on ?x ?y) (clear ?x))
    :effect (and (holding ?r ?x) (clear ?y) (not (on ?x ?y)) (not (clear ?x))
                 (not (handempty ?r))))

  (:action place
    :parameters (?r - arm ?x - block)
    :precondition (holding ?r ?x)
    :effect (and (ontable ?x) (clear ?x) (handempty ?r) (not (holding ?r ?x))))

  (:action put-on-shelf
    :parameters (?r - arm ?x - block)
    :precondition (holding ?r ?x)
    :effect (and (onshelf ?x) (clear ?x) (handempty ?r) (not (holding ?r ?x))))

  (:action stack
    :parameters (?r - arm ?x - block ?y - block)
    :precondition (and (holding ?r ?x) (clear ?y))
    :effect (and (on ?x ?y) (clear ?x) (handempty ?r) (not (holding ?r ?x)) (not (clear ?y)))))
