attribute vec3 aVertexPosition;
attribute vec3 aNormalPosition;
attribute vec2 aTextureCoord;

uniform mat4 uModelMatrix;
uniform mat4 uViewMatrix;
uniform mat4 uProjectionMatrix;
uniform mat4 uLightMVP;

varying highp vec2 vTextureCoord;
varying highp vec3 vFragPos;
varying highp vec3 vNormal;
varying highp vec4 vPositionFromLight;

void main(void) {
  vec4 world = uModelMatrix * vec4(aVertexPosition, 1.0);
  vFragPos = world.xyz;
  vNormal = (uModelMatrix * vec4(aNormalPosition, 0.0)).xyz;
  vTextureCoord = aTextureCoord;
  gl_Position = uProjectionMatrix * uViewMatrix * world;
  vPositionFromLight = uLightMVP * vec4(aVertexPosition, 1.0);
}
