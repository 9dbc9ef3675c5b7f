/* Found by reyes-fuzz (sl target, 2026-12-05): a function-like macro whose parameter
   appears 64 times, nested five deep in its own arguments, makes 64^5 (1e9) copies. The
   expansion budget (then 4 M tokens) was checked only after each macro's whole body was
   built, and the last level alone took 19.5 GB and 77 s before the error. Now checked as
   the body is built, against 1 M tokens: rejected with one error in 0.12 s and 116 MB. */
#define MIX64(a, b, x) ((a) * (1 - (x)) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x) + (b) * (x))

surface blowup() {
    Ci = MIX64(1, MIX64(1, MIX64(1, MIX64(1, MIX64(1, 0.5, s), t), s), t), s);
}
