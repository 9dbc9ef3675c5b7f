/* softspot: a spot light written for reyes-render (issue #30). Light from `from` toward `to`
 * inside a cone of half-angle `coneangle`, its edge softened over `penumbra` radians, falling
 * off with the square of the distance. */
light softspot(float intensity = 1; color lightcolor = 1;
               point from = point "shader" (0, 0, 0), to = point "shader" (0, 0, 1);
               float coneangle = radians(25), penumbra = radians(8))
{
    uniform vector axis = normalize(to - from);
    illuminate(from, axis, coneangle) {
        float cosangle = (L . axis) / length(L);
        float edge = smoothstep(cos(coneangle), cos(coneangle - penumbra), cosangle);
        Cl = intensity * lightcolor * edge / (L . L);
    }
}
