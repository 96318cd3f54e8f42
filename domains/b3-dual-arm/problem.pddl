; B3 template task: both blocks on the left table (only the left arm reaches it); build a on b on
; the right table (only the right arm reaches it), handing the blocks over in the middle.
(define (problem b3-dual-arm-template)
  (:domain b3-dual-arm)
  (:objects
    left right - arm
    a b - block
    left-table handover right-table - region)
  (:init
    (ontable a) (ontable b) (clear a) (clear b)
    (at a left-table) (at b left-table)
    (handempty left) (handempty right)
    (reaches left left-table) (reaches left handover)
    (reaches right handover) (reaches right right-table))
  (:goal (and (on a b) (at b right-table))))
