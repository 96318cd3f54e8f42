; B1 template task in the paper's naming: four blocks on the table, build a on b on c on d.
(define (problem b1-paper-naming-template)
  (:domain b1-paper-naming)
  (:objects panda a b c d)
  (:init
    (arm panda) (block a) (block b) (block c) (block d)
    (on-table a) (on-table b) (on-table c) (on-table d)
    (clear a) (clear b) (clear c) (clear d)
    (empty panda))
  (:goal (and (on-block a b) (on-block b c) (on-block c d))))
