; expect 6:16 preference
(define (problem pr)
  (:domain base)
  (:objects o)
  (:init (p o))
  (:goal (and (preference g1 (q)))))
