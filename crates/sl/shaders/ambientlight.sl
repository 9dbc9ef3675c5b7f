/* ambientlight: light from no direction (no illuminate or solar), reaching ambient(). */
light ambientlight(float intensity = 1; color lightcolor = 1;)
{
    Cl = intensity * lightcolor;
}
