; Carrot-and-onion soup: fetch both vegetables from the fridge, chop them, wash the
; knife, put them in the pot on the stove, cook, and pour the soup into the bowl on
; the dining table. The fridge must end up shut.
;
;   pantry -- fridge -- counter -- sink
;                          |       |
;            table  --  stove -----+
(define (problem carrot-onion-soup)
  (:domain kitchen)
  (:objects
    chef - robot
    fridge pantry counter sink stove table - station
    carrot onion tomato potato - ingredient
    kitchen-knife - knife
    stock-pot - pot
    soup-bowl side-plate - bowl)
  (:init
    ; layout (static)
    (adjacent pantry fridge) (adjacent fridge pantry)
    (adjacent fridge counter) (adjacent counter fridge)
    (adjacent counter sink) (adjacent sink counter)
    (adjacent counter stove) (adjacent stove counter)
    (adjacent sink stove) (adjacent stove sink)
    (adjacent stove table) (adjacent table stove)
    (has-door fridge)
    (has-cutting-board counter)
    (has-burner stove)
    (has-tap sink)
    (recipe carrot onion)
    ; the cook
    (robot-at chef counter)
    (hand-empty chef)
    ; items
    (item-at carrot fridge) (item-at onion fridge) (item-at tomato fridge)
    (item-at potato pantry)
    (item-at kitchen-knife counter) (clean kitchen-knife)
    (item-at stock-pot stove)
    (item-at soup-bowl table) (item-at side-plate table)
    (closed fridge))
  (:goal (and
    (in-pot carrot stock-pot)
    (in-pot onion stock-pot)
    (cooked stock-pot)
    (full soup-bowl)
    (item-at soup-bowl table)
    (clean kitchen-knife)
    (closed fridge))))
