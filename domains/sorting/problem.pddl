; Two mixed stacks in the pile (blue b1 on red r1, red r2 on blue b2); the goal is red r1 on r2 in
; the red tray and blue b1 on b2 in the blue tray.
(define (problem sorting-two-colours)
  (:domain sorting)
  (:objects
    panda - arm
    b1 b2 r1 r2 - cube
    pile red-tray blue-tray - region)
  (:init
    (ontable r1) (on b1 r1) (clear b1)
    (ontable b2) (on r2 b2) (clear r2)
    (at r1 pile) (at b1 pile) (at b2 pile) (at r2 pile)
    (handempty panda))
  (:goal (and (on r1 r2) (at r2 red-tray) (on b1 b2) (at b2 blue-tray))))
