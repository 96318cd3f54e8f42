; Sorting: a gripper puts coloured cubes into the tray of their colour. Nothing puts a cube
; into a tray of another colour, but a person can (a disturbance the domain does not model).
(define (domain sorting)
  (:requirements :strips :typing)
  (:types cube tray colour)
  (:predicates
    (cube-colour ?c - cube ?k - colour)   ; static
    (tray-colour ?t - tray ?k - colour)   ; static
    (on-table ?c - cube)
    (in ?c - cube ?t - tray)
    (holding ?c - cube)
    (hand-empty))
  (:action pick-from-table
    :parameters (?c - cube)
    :precondition (and (on-table ?c) (hand-empty))
    :effect (and (holding ?c) (not (on-table ?c)) (not (hand-empty))))
  (:action pick-from-tray
    :parameters (?c - cube ?t - tray)
    :precondition (and (in ?c ?t) (hand-empty))
    :effect (and (holding ?c) (not (in ?c ?t)) (not (hand-empty))))
  (:action put-in-tray
    :parameters (?c - cube ?t - tray ?k - colour)
    :precondition (and (holding ?c) (cube-colour ?c ?k) (tray-colour ?t ?k))
    :effect (and (in ?c ?t) (hand-empty) (not (holding ?c)))))
