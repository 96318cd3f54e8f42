; B1 Tower Construction, written the way the paper's own code names things: untyped objects
; guarded by type predicates, (inhand arm block), (on-block ?b ?c), (on-table ?b), (empty arm),
; and actions whose block comes first. The robot reads it through motions.json; nothing in the
; library knows these names.
(define (domain b1-paper-naming)
  (:requirements :strips :equality)
  (:predicates
    (block ?b) (arm ?a)
    (on-block ?b ?c)
    (on-table ?b)
    (clear ?b)
    (inhand ?a ?b)
    (empty ?a))

  (:action pick-up
    :parameters (?b ?a)
    :precondition (and (block ?b) (arm ?a) (empty ?a) (clear ?b) (on-table ?b))
    :effect (and (inhand ?a ?b) (not (empty ?a)) (not (clear ?b)) (not (on-table ?b))))

  (:action put-down
    :parameters (?b ?a)
    :precondition (and (block ?b) (arm ?a) (inhand ?a ?b))
    :effect (and (on-table ?b) (clear ?b) (empty ?a) (not (inhand ?a ?b))))

  (:action put-on
    :parameters (?b ?c ?a)
    :precondition (and (block ?b) (block ?c) (arm ?a) (not (= ?b ?c)) (inhand ?a ?b) (clear ?c))
    :effect (and (on-block ?b ?c) (clear ?b) (empty ?a) (not (inhand ?a ?b)) (not (clear ?c))))

  (:action take-off
    :parameters (?b ?c ?a)
    :precondition (and (block ?b) (block ?c) (arm ?a) (not (= ?b ?c)) (empty ?a)
                       (on-block ?b ?c) (clear ?b))
    :effect (and (inhand ?a ?b) (clear ?c) (not (on-block ?b ?c)) (not (clear ?b))
                 (not (empty ?a)))))
