attribute vec3 aVertexPosition;
attribute vec3 aNormalPosition;
attribute vec2 aTextureCoord;

uniform mat4 uLightMVP;
// The drawn object's model matrix, under a name of the page's own.
uniform mat4 uLightModel;

varying highp vec3 vWorldPos;

void main(void) {
  vWorldPos = (uLightModel * vec4(aVertexPosition, 1.0)).xyz;
  gl_Position = uLightMVP * vec4(aVertexPosition, 1.0);
}
