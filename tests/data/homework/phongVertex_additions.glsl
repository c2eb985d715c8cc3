attribute vec3 aVertexPosition;
attribute vec3 aNormalPosition;
attribute vec2 aTextureCoord;

uniform mat4 uModelMatrix;
uniform mat4 uViewMatrix;
uniform mat4 uProjectionMatrix;
uniform mat4 uLightMVP;
uniform float uNormalOffsetWorld;

varying highp vec2 vTextureCoord;
varying highp vec3 vFragPos;
varying highp vec3 vNormal;
varying highp vec4 vPositionFromLight;
// A student's own: the view depth, and the light-space position pushed along the normal.
varying highp float vDepthView;
varying highp vec4 vOffsetFromLight;

void main(void) {
  vec4 world = uModelMatrix * vec4(aVertexPosition, 1.0);
  vFragPos = world.xyz;
  vNormal = (uModelMatrix * vec4(aNormalPosition, 0.0)).xyz;
  vTextureCoord = aTextureCoord;
  vec4 view = uViewMatrix * world;
  vDepthView = -view.z;
  gl_Position = uProjectionMatrix * view;
  vPositionFromLight = uLightMVP * vec4(aVertexPosition, 1.0);
  vOffsetFromLight = uLightMVP * vec4(aVertexPosition + uNormalOffsetWorld * aNormalPosition, 1.0);
}
