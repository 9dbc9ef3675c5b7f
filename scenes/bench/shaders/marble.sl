/* marble: an fBm marble surface written for reyes-render's shaded benchmark (issue #30).
 * Four octaves of gradient noise in shader space perturb a sine of x into veins, mixed
 * between a base and a vein colour; lit as plastic. */
surface marble(float Ka = 1, Kd = 0.7, Ks = 0.5, roughness = 0.1;
               float frequency = 2, turbulence = 3;
               color veincolor = color (0.25, 0.2, 0.35))
{
    point Pshad = transform("shader", P) * frequency;
    float sum = 0, amp = 1, i;
    for (i = 0; i < 4; i += 1) {
        sum += amp * (2 * noise(Pshad) - 1);
        Pshad *= 2;
        amp *= 0.5;
    }
    float vein = pow(abs(sin(xcomp(Pshad) / 16 * PI + turbulence * sum)), 0.4);
    color base = mix(veincolor, Cs, vein);
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    Oi = Os;
    Ci = Os * (base * (Ka * ambient() + Kd * diffuse(Nf)) + Ks * specular(Nf, V, roughness));
}
