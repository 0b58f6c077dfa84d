#pragma once
// The Illinois variant of regula falsi, the bracketing root finder the enriched points use where
// a function is piecewise smooth and Newton would need its kinks (the onset of a band inside an
// increment, docs/model.md pitfall 1; the snap-back release's integrity). Each step takes the
// secant's root c of the bracket [a, b] (g(a) = ga < 0 < gb = g(b)); an end that stays twice in a
// row has its value halved, so the bracket shrinks from both sides.
namespace ecm {

// Searches [a, b] (updated in place) while wide(a, b) holds, for at most maxIterations steps;
// g(c) evaluates the function (and may keep what it computed). True as soon as done(g(c)) holds
// (c was the last point evaluated); false when the bracket narrowed or the steps ran out.
template <class G, class Wide, class Done>
bool illinois(G&& g, double& a, double& b, double ga, double gb, int maxIterations, Wide&& wide, Done&& done) {
  int side = 0;
  for (int it = 0; it < maxIterations && wide(a, b); ++it) {
    const double c = (a * gb - b * ga) / (gb - ga);
    const double gc = g(c);
    if (done(gc)) return true;
    if (gc < 0.0) {
      a = c, ga = gc;
      if (side == -1) gb *= 0.5;
      side = -1;
    } else {
      b = c, gb = gc;
      if (side == +1) ga *= 0.5;
      side = +1;
    }
  }
  return false;
}

}  // namespace ecm
