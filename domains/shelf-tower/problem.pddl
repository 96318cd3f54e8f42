; Block d stands on the shelf; a, b and c are on the table. The goal is the tower a on b on c on
; the shelf, with d back on the table.
(define (problem shelf-tower-abc)
  (:domain shelf-tower)
  (:objects
    panda - arm
    a b c d - block)
  (:init
    (ontable a) (ontable b) (ontable c) (onshelf d)
    (clear a) (clear b) (clear c) (clear d)
    (handempty panda))
  (:goal (and (on a b) (on b c) (onshelf c) (ontable d))))
