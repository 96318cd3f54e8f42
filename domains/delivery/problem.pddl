; Morning round: four parcels leave the depot, two of them for old-town addresses only
; the cargo bike reaches; a customer return waits at the harbour and goes back to the
; depot. At the end the van is back at the depot and the bike at the market.
;
;                 ring-north ---- elm-street
;                /          \
;   depot ------+            market ====== church-lane
;                \          /     \\            ||
;                 ring-south       ======== castle-hill
;                     |
;                  harbour
;   -- roads (vans), == lanes (cargo bike)
(define (problem morning-round)
  (:domain delivery)
  (:objects
    depot ring-north ring-south elm-street harbour market church-lane castle-hill - place
    van1 - van
    cargo-bike - bike
    p1 p2 p3 p4 return1 - parcel)
  (:init
    ; roads, both directions
    (road depot ring-north) (road ring-north depot)
    (road depot ring-south) (road ring-south depot)
    (road ring-north elm-street) (road elm-street ring-north)
    (road ring-north market) (road market ring-north)
    (road ring-south market) (road market ring-south)
    (road ring-south harbour) (road harbour ring-south)
    ; old-town lanes, both directions
    (lane market church-lane) (lane church-lane market)
    (lane market castle-hill) (lane castle-hill market)
    (lane church-lane castle-hill) (lane castle-hill church-lane)
    ; orders
    (destination p1 elm-street)
    (destination p2 harbour)
    (destination p3 church-lane)
    (destination p4 castle-hill)
    ; vehicles
    (at van1 depot)
    (at cargo-bike market) (basket-empty cargo-bike)
    ; parcels
    (parcel-at p1 depot) (parcel-at p2 depot) (parcel-at p3 depot) (parcel-at p4 depot)
    (parcel-at return1 harbour))
  (:goal (and
    (delivered p1) (delivered p2) (delivered p3) (delivered p4)
    (parcel-at return1 depot)
    (at van1 depot)
    (at cargo-bike market))))
