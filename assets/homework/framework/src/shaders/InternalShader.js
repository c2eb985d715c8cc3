// shadowlab's own copy of the framework's interface: the light cube's shaders.
const LightCubeVertexShader = `
attribute vec3 aVertexPosition;
uniform mat4 uModelMatrix;
uniform mat4 uViewMatrix;
uniform mat4 uProjectionMatrix;
void main(void) {
  gl_Position = uProjectionMatrix * uViewMatrix * uModelMatrix * vec4(aVertexPosition, 1.0);
}
`;

const LightCubeFragmentShader = `
#ifdef GL_ES
precision mediump float;
#endif
uniform float uLigIntensity;
uniform vec3 uLightColor;
void main(void) {
  gl_FragColor = vec4(uLightColor, 1.0);
}
`;
