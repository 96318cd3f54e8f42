; A small domain for what the IPC files lack: negative preconditions, equality, disjunctive
; preconditions, constants, action costs (constant and static function terms).
(define (domain rooms)
  (:requirements :strips :typing :negative-preconditions :equality
                 :disjunctive-preconditions :action-costs)
  (:types room key - object)
  (:constants hall - room)
  (:predicates (at ?r - room) (door ?a ?b - room) (locked ?r - room) (has ?k - key)
               (key-at ?k - key ?r - room) (opens ?k - key ?r - room) (visited ?r - room))
  (:functions (total-cost) - number (dist ?a ?b - room) - number)
  (:action move
    :parameters (?a ?b - room)
    :precondition (and (at ?a) (not (= ?a ?b)) (or (door ?a ?b) (door ?b ?a)) (not (locked ?b)))
    :effect (and (not (at ?a)) (at ?b) (visited ?b) (increase (total-cost) (dist ?a ?b))))
  (:action take
    :parameters (?k - key ?r - room)
    :precondition (and (at ?r) (key-at ?k ?r))
    :effect (and (has ?k) (not (key-at ?k ?r)) (increase (total-cost) 0)))
  (:action unlock
    :parameters (?k - key ?a ?b - room)
    :precondition (and (at ?a) (has ?k) (opens ?k ?b) (or (door ?a ?b) (door ?b ?a)) (locked ?b))
    :effect (and (not (locked ?b)) (increase (total-cost) 2)))
  (:action wait
    :parameters (?a ?b - room)
    :precondition (and (at ?a) (= ?a ?b))
    :effect (and (visited ?b) (increase (total-cost) 1))))
