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
uniform bool uShadows;                  // darken where the root hides the key light
uniform mat4 uLightViewProj;            // plate [mm] -> light clip space
uniform sampler2DShadow uShadowMap;     // root depth from the light (compare mode)
uniform float uShadowTexel;             // 1 / shadow map size

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
  if (uShadows) {
    // 3 x 3 percentage-closer filter (each tap bilinear in hardware) for a soft edge
    vec4 lc = uLightViewProj * vec4(vPlate, 0.0, 1.0);
    vec3 q = lc.xyz / lc.w * 0.5 + 0.5;
    float lit = 0.0;
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j)
        lit += texture(uShadowMap, vec3(q.xy + vec2(i, j) * uShadowTexel, min(q.z, 1.0) - 2e-4));
    lit /= 9.0;
    col *= mix(0.58, 1.0, lit);
  }
  fragColour = vec4(col, 1.0);
}
