; B2 template task: block a in reach, block b beyond reach, the hook in reach; all blocks on the shelf.
(define (problem b2-workspace-reach-template)
  (:domain b2-workspace-reach)
  (:objects
    panda - arm
    a b - block
    hook - hook)
  (:init
    (ontable a) (ontable b) (ontable hook)
    (inreach panda a) (inreach panda hook)
    (handempty panda))
  (:goal (and (onshelf a) (onshelf b))))
