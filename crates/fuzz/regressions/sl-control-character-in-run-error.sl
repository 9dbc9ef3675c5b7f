/* A coordinate-system name holding a carriage return: the run error quoted it raw, on two
   lines. */
surface cr() {
    point q = transform("shder", P);
    Ci = color(xcomp(q), 0, 0);
}
