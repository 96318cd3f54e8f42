//! LQT-CP motion skills (paper §III-B, eqs. 1–4) and the classic DMP used for comparison.
