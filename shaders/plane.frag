#version 450 core
// plate colour with an anti-aliased millimetre grid; lines fade out where they get denser than the
// pixels (far side of the perspective view) instead of aliasing
in vec2 vPlate;

uniform float uGrid;        // spacing [mm]
uniform int uMajorEvery;    // every n-th line uses the major colour
uniform float uLineWidth;   // [px]
uniform vec3 uColour;
uniform vec3 uLine;
uniform vec3 uMajor;

out vec4 fragColour;

void main() {
  vec2 q = vPlate / uGrid;
  vec2 fw = max(fwidth(q), vec2(1e-6));
  vec2 dist = abs(fract(q + 0.5) - 0.5) / fw;            // to the nearest line [px]
  vec2 cover = clamp(0.5 * uLineWidth + 0.5 - dist, 0.0, 1.0);
  cover *= 1.0 - smoothstep(0.12, 0.35, fw);              // fade when lines are < 3-8 px apart
  vec2 idx = floor(q + 0.5);
  vec2 major = vec2(mod(idx.x, float(uMajorEvery)) == 0.0 ? 1.0 : 0.0,
                    mod(idx.y, float(uMajorEvery)) == 0.0 ? 1.0 : 0.0);
  vec3 col = uColour;
  col = mix(col, mix(uLine, uMajor, major.x), cover.x);
  col = mix(col, mix(uLine, uMajor, major.y), cover.y);
  fragColour = vec4(col, 1.0);
}
