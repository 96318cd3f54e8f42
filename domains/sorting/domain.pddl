; Sorting: one arm takes cubes of two colours from a mixed pile and builds one stack of each colour
; in the tray of that colour. Table regions (the pile, the trays) are seen by the camera: a cube
; resting with its centre inside a region is `at` it, stacked or not.
(define (domain sorting)
  (:requirements :strips :typing)
  (:types arm cube region)
  (:predicates
    (on ?x - cube ?y - cube)
    (ontable ?x - cube)
    (clear ?x - cube)
    (holding ?r - arm ?x - cube)
    (handempty ?r - arm)
    (at ?x - cube ?p - region))

  (:action pick
    :parameters (?r - arm ?x - cube ?p - region)
    :precondition (and (handempty ?r) (clear ?x) (ontable ?x) (at ?x ?p))
    :effect (and (holding ?r ?x) (not (handempty ?r)) (not (clear ?x)) (not (ontable ?x))
                 (not (at ?x ?p))))

  (:action place
    :parameters (?r - arm ?x - cube ?p - region)
    :precondition (holding ?r ?x)
    :effect (and (ontable ?x) (at ?x ?p) (clear ?x) (handempty ?r) (not (holding ?r ?x))))

  (:action stack
    :parameters (?r - arm ?x - cube ?y - cube ?p - region)
    :precondition (and (holding ?r ?x) (clear ?y) (at ?y ?p))
    :effect (and (on ?x ?y) (at ?x ?p) (clear ?x) (handempty ?r) (not (holding ?r ?x))
                 (not (clear ?y))))

  (:action unstack
    :parameters (?r - arm ?x - cube ?y - cube ?p - region)
    :precondition (and (handempty ?r) (on ?x ?y) (clear ?x) (at ?x ?p))
    :effect (and (holding ?r ?x) (clear ?y) (not (on ?x ?y)) (not (clear ?x))
                 (not (handempty ?r)) (not (at ?x ?p)))))
