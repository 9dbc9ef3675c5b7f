/* haze: an atmosphere written for reyes-render (issue #30). Blends toward a haze colour with
 * the distance travelled beyond `start`, exponentially over `distance`. */
volume haze(float start = 2, distance = 12; color hazecolor = color (0.55, 0.6, 0.7))
{
    float d = 1 - exp(-max(0, length(I) - start) / distance);
    Ci = mix(Ci, Oi * hazecolor, d);
}
