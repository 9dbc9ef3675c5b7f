/* Seed for the sl target: preprocessor, user functions, loops, arrays, noise, splines. */
#define OCTAVES 4
#define MIXC(a, b, x) ((a) * (1 - (x)) + (b) * (x))
#define STR(x) #x
#if OCTAVES > 2 && defined(OCTAVES)
#define FBM 1
#else
#define FBM 0
#endif

float fbm(point p; uniform float octaves; output float last) {
    float sum = 0, amp = 0.5, i;
    point q = p;
    for (i = 0; i < octaves; i += 1) {
        last = noise(q);
        sum += amp * (last - 0.5);
        amp *= 0.5;
        q *= 2.03;
        if (sum > 10) break;
    }
    return sum;
}

surface patterns(float Ka = 1, Kd = 0.8, scale = 4; color c1 = color(0.8, 0.3, 0.1);
                 color c2 = color "hsv" (0.6, 0.5, 0.9); string name = STR(marble);
                 float weights[3] = {0.2, 0.3, 0.5}; output varying float pat = 0) {
    point Pshad = transform("shader", P) * scale;
    float last;
    float f = FBM ? fbm(Pshad, OCTAVES, last) : 0;
    float k = 0, j = 0;
    while (j < 3) {
        k += weights[j] * cellnoise(Pshad + j);
        j += 1;
        if (k > 0.9) continue;
    }
    pat = mod(floor(s * 8) + floor(t * 8), 2);
    float m = spline("catmull-rom", clamp(f + 0.5, 0, 1), 0, 0.2, 0.5, 0.7, 1, 1);
    color base = MIXC(c1, c2, smoothstep(0.2, 0.8, m));
    base = mix(base, color(pnoise(Pshad, point(4, 4, 4))), 0.1 * k);
    normal Nf = faceforward(normalize(N), I);
    Oi = Os;
    Ci = Os * base * (Ka * ambient() + Kd * diffuse(Nf)) * (pat > 0.5 ? 1 : 0.8);
    if (name == "marble") Ci *= 1.0;
}
