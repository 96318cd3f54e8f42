(define (problem two-cubes)
  (:domain sorting)
  (:objects red-cube blue-cube - cube red-tray blue-tray - tray red blue - colour)
  (:init
    (cube-colour red-cube red) (cube-colour blue-cube blue)
    (tray-colour red-tray red) (tray-colour blue-tray blue)
    (on-table red-cube) (on-table blue-cube) (hand-empty))
  (:goal (and (in red-cube red-tray) (in blue-cube blue-tray))))
