; B1 template task: four blocks on the table, build the tower a on b on c on d.
(define (problem b1-tower-template)
  (:domain b1-tower)
  (:objects
    panda - arm
    a b c d - block)
  (:init
    (ontable a) (ontable b) (ontable c) (ontable d)
    (clear a) (clear b) (clear c) (clear d)
    (handempty panda))
  (:goal (and (on a b) (on b c) (on c d))))
