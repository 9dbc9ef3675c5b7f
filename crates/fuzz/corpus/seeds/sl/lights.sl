/* Seed for the sl target: a light with a cone, shadows off, message passing. */
light conelight(float intensity = 1; color lightcolor = 1; point from = point "shader" (0, 0, 0);
                point to = point "shader" (0, 0, 1); float coneangle = radians(30);
                float conedelta = radians(5); output float __nondiffuse = 0;
                string __category = "spot") {
    uniform vector A = normalize(to - from);
    illuminate(from, A, coneangle) {
        float cosangle = L . A / length(L);
        float atten = smoothstep(cos(coneangle), cos(coneangle - conedelta), cosangle);
        Cl = atten * intensity * lightcolor / (L . L);
    }
}
