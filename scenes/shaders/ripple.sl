/* ripple: a displacement written for reyes-render (issue #30). Concentric waves about the
 * surface point where (s, t) = center, fading with distance; the normal is recomputed from
 * the moved points. The largest displacement is amplitude (declare a displacementbound of at
 * least that). */
displacement ripple(float amplitude = 0.05, wavelength = 0.1, fade = 2;
                    float centers = 0.5, centert = 0.5)
{
    float d = distance(point (s, t, 0), point (centers, centert, 0));
    float h = amplitude * cos(2 * PI * d / wavelength) * exp(-fade * d);
    P += h * normalize(N);
    N = calculatenormal(P);
}
