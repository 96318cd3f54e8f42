; Kitchen: a one-armed robot cook makes vegetable soup.
;
; The cook walks between kitchen stations (fridge, pantry, counter, sink, stove,
; dining table), carries one item at a time, chops vegetables on the cutting board
; with a knife held in its hand, tips chopped vegetables into the pot, cooks the pot
; on the burner, pours the soup into a bowl and washes the knife at the sink.
; Unit-cost typed STRIPS with negative preconditions.
(define (domain kitchen)
  (:requirements :strips :typing :negative-preconditions)

  (:types
    robot station item - object
    ingredient knife pot bowl - item)

  (:predicates
    ; --- layout (static) ---
    (adjacent ?from - station ?to - station)  ; the cook can walk from ?from to ?to
    (has-door ?s - station)                   ; a storage station with a door (the fridge)
    (has-cutting-board ?s - station)          ; where vegetables are chopped
    (has-burner ?s - station)                 ; where a pot is cooked
    (has-tap ?s - station)                    ; where tools are washed
    (recipe ?g1 - ingredient ?g2 - ingredient) ; the soup is made of ?g1 and ?g2
    ; --- the cook ---
    (robot-at ?r - robot ?s - station)
    (hand-empty ?r - robot)
    (holding ?r - robot ?i - item)
    ; --- items and stations ---
    (item-at ?i - item ?s - station)          ; ?i stands at (or inside) ?s
    (closed ?s - station)                     ; the door of ?s is shut
    (chopped ?g - ingredient)
    (clean ?k - knife)
    (in-pot ?g - ingredient ?p - pot)
    (cooked ?p - pot)
    (full ?b - bowl))                         ; ?b holds served soup

  ; Walk to a neighbouring station.
  (:action move
    :parameters (?r - robot ?from - station ?to - station)
    :precondition (and (robot-at ?r ?from) (adjacent ?from ?to))
    :effect (and (robot-at ?r ?to) (not (robot-at ?r ?from))))

  ; Open a closed door; the hand must be free to pull the handle.
  (:action open
    :parameters (?r - robot ?s - station)
    :precondition (and (robot-at ?r ?s) (has-door ?s) (closed ?s) (hand-empty ?r))
    :effect (not (closed ?s)))

  ; Push a door shut (possible with something in the hand).
  (:action close
    :parameters (?r - robot ?s - station)
    :precondition (and (robot-at ?r ?s) (has-door ?s) (not (closed ?s)))
    :effect (closed ?s))

  ; Take an item from the station the cook stands at (not through a shut door).
  (:action pick
    :parameters (?r - robot ?i - item ?s - station)
    :precondition (and (robot-at ?r ?s) (item-at ?i ?s) (hand-empty ?r) (not (closed ?s)))
    :effect (and (holding ?r ?i) (not (item-at ?i ?s)) (not (hand-empty ?r))))

  ; Put the held item down at (or into) the station the cook stands at.
  (:action place
    :parameters (?r - robot ?i - item ?s - station)
    :precondition (and (robot-at ?r ?s) (holding ?r ?i) (not (closed ?s)))
    :effect (and (item-at ?i ?s) (hand-empty ?r) (not (holding ?r ?i))))

  ; Chop a vegetable lying on the cutting board with the knife in hand; the knife gets dirty.
  (:action chop
    :parameters (?r - robot ?g - ingredient ?k - knife ?s - station)
    :precondition (and (robot-at ?r ?s) (has-cutting-board ?s) (item-at ?g ?s)
                       (holding ?r ?k) (not (chopped ?g)))
    :effect (and (chopped ?g) (not (clean ?k))))

  ; Drop the held chopped vegetable into a pot standing at the cook's station (before cooking).
  (:action add
    :parameters (?r - robot ?g - ingredient ?p - pot ?s - station)
    :precondition (and (robot-at ?r ?s) (holding ?r ?g) (chopped ?g)
                       (item-at ?p ?s) (not (cooked ?p)))
    :effect (and (in-pot ?g ?p) (hand-empty ?r) (not (holding ?r ?g))))

  ; Cook the pot on a burner once both vegetables of the recipe are in it.
  (:action cook
    :parameters (?r - robot ?p - pot ?g1 - ingredient ?g2 - ingredient ?s - station)
    :precondition (and (robot-at ?r ?s) (has-burner ?s) (item-at ?p ?s) (not (cooked ?p))
                       (recipe ?g1 ?g2) (in-pot ?g1 ?p) (in-pot ?g2 ?p))
    :effect (cooked ?p))

  ; Pour soup from the held, cooked pot into an empty bowl at the cook's station.
  (:action serve
    :parameters (?r - robot ?p - pot ?b - bowl ?s - station)
    :precondition (and (robot-at ?r ?s) (holding ?r ?p) (cooked ?p)
                       (item-at ?b ?s) (not (full ?b)))
    :effect (full ?b))

  ; Rinse the held knife under the tap.
  (:action wash
    :parameters (?r - robot ?k - knife ?s - station)
    :precondition (and (robot-at ?r ?s) (has-tap ?s) (holding ?r ?k) (not (clean ?k)))
    :effect (clean ?k)))
