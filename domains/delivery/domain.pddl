; Delivery: vans and a cargo bike deliver parcels in a small town.
;
; Vans drive along roads and carry any number of parcels. The old town is closed to
; cars: a cargo bike, parked at the market square, rides the old-town lanes and carries
; one parcel at a time. A parcel is delivered by handing it over at its destination
; straight from the vehicle; it can also be unloaded anywhere (e.g. at the market hub,
; to hand it over to the bike) and loaded again. Unit-cost typed STRIPS.
(define (domain delivery)
  (:requirements :strips :typing)

  (:types
    place vehicle parcel - object
    van bike - vehicle)

  (:predicates
    ; --- town map and orders (static) ---
    (road ?from - place ?to - place)        ; a street vans (and only vans) drive along
    (lane ?from - place ?to - place)        ; a route the cargo bike rides along
    (destination ?p - parcel ?a - place)    ; the address ?p must be delivered to
    ; --- vehicles and parcels ---
    (at ?v - vehicle ?l - place)
    (parcel-at ?p - parcel ?l - place)      ; ?p lies at ?l (depot shelf, hub, kerb)
    (in ?p - parcel ?v - vehicle)
    (basket-empty ?b - bike)                ; the bike's cargo box is free
    (delivered ?p - parcel))

  ; Drive a van to a neighbouring place.
  (:action drive
    :parameters (?v - van ?from - place ?to - place)
    :precondition (and (at ?v ?from) (road ?from ?to))
    :effect (and (at ?v ?to) (not (at ?v ?from))))

  ; Ride the cargo bike to a neighbouring place.
  (:action ride
    :parameters (?b - bike ?from - place ?to - place)
    :precondition (and (at ?b ?from) (lane ?from ?to))
    :effect (and (at ?b ?to) (not (at ?b ?from))))

  ; Put a parcel into a van.
  (:action load
    :parameters (?p - parcel ?v - van ?l - place)
    :precondition (and (at ?v ?l) (parcel-at ?p ?l))
    :effect (and (in ?p ?v) (not (parcel-at ?p ?l))))

  ; Take a parcel out of a van and leave it at the van's place.
  (:action unload
    :parameters (?p - parcel ?v - van ?l - place)
    :precondition (and (at ?v ?l) (in ?p ?v))
    :effect (and (parcel-at ?p ?l) (not (in ?p ?v))))

  ; Put a parcel into the bike's empty cargo box.
  (:action load-bike
    :parameters (?p - parcel ?b - bike ?l - place)
    :precondition (and (at ?b ?l) (parcel-at ?p ?l) (basket-empty ?b))
    :effect (and (in ?p ?b) (not (parcel-at ?p ?l)) (not (basket-empty ?b))))

  ; Take the parcel out of the bike's cargo box and leave it at the bike's place.
  (:action unload-bike
    :parameters (?p - parcel ?b - bike ?l - place)
    :precondition (and (at ?b ?l) (in ?p ?b))
    :effect (and (parcel-at ?p ?l) (basket-empty ?b) (not (in ?p ?b))))

  ; Hand a parcel over at its address, straight from the van.
  (:action deliver
    :parameters (?p - parcel ?v - van ?a - place)
    :precondition (and (at ?v ?a) (in ?p ?v) (destination ?p ?a))
    :effect (and (delivered ?p) (not (in ?p ?v))))

  ; Hand a parcel over at its address, straight from the bike's cargo box.
  (:action deliver-by-bike
    :parameters (?p - parcel ?b - bike ?a - place)
    :precondition (and (at ?b ?a) (in ?p ?b) (destination ?p ?a))
    :effect (and (delivered ?p) (basket-empty ?b) (not (in ?p ?b)))))
