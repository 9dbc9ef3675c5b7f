/* Seed for the sl target: a displacement, bump, and a volume and an imager in one corpus. */
displacement ripples(float Km = 0.05, freq = 10) {
    float h = Km * sin(freq * s * 2 * PI) * cos(freq * t * 2 * PI);
    P += h * normalize(N);
    N = calculatenormal(P);
}
