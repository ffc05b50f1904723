#version 450 core
// root tube, caps and whiskers: positions in plate coordinates [mm]
layout(location = 0) in vec3 aPos;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aSide;     // (cos phi, sin phi) of the normal in the (d1, d2) plane
layout(location = 3) in vec3 aColour;
layout(location = 4) in float aStriped;

uniform mat4 uView;
uniform mat4 uProj;

out vec3 vPlate;       // plate coordinates [mm], for the shadow map
out vec3 vNormalPlate;
out vec3 vPosEye;
out vec3 vNormalEye;
out vec2 vSide;
out vec3 vColour;
out float vStriped;

void main() {
  vPlate = aPos;
  vNormalPlate = aNormal;
  vec4 pe = uView * vec4(aPos, 1.0);
  vPosEye = pe.xyz;
  vNormalEye = mat3(uView) * aNormal;   // the view matrix is a rotation plus a translation
  vSide = aSide;
  vColour = aColour;
  vStriped = aStriped;
  gl_Position = uProj * pe;
}
