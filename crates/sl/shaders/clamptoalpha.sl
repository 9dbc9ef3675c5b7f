/* clamptoalpha: keeps each channel between 0 and alpha (valid premultiplied colour). */
imager clamptoalpha()
{
    Ci = clamp(Ci, color 0, color alpha);
    Oi = clamp(Oi, color 0, color alpha);
}
