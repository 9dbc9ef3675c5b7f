volume haze(float distance = 5; color background = color(0.5, 0.6, 0.7)) {
    float d = 1 - exp(-length(I) / distance);
    Ci = mix(Ci, background, d);
    Oi = mix(Oi, color(1, 1, 1), d);
}
