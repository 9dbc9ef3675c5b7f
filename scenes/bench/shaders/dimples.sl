/* dimples: a bumpy-style displacement written for reyes-render's shaded benchmark (issue
 * #30). Moves each point along its normal by Km times a noise of its shader-space position
 * (at most Km / 2 either way: declare a displacementbound of at least that) and recomputes
 * the normal from the moved points. */
displacement dimples(float Km = 0.03, frequency = 6)
{
    point Pshad = transform("shader", P) * frequency;
    float h = Km * (noise(Pshad) - 0.5);
    P += h * normalize(N);
    N = calculatenormal(P);
}
