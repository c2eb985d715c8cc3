// The framework's directional light with a CalcLightMVP of shadowlab's own writing: the light
// looks from its position at its focal point through an orthographic box 200 world units wide,
// from 0.01 to 400 along its axis (the box shadowlab's check scene uses by default).
class DirectionalLight {
  constructor(lightIntensity, lightColor, lightPos, focalPoint, lightUp, hasShadowMap, gl) {
    this.mesh = Mesh.cube(setTransform(0, 0, 0, 0.2, 0.2, 0.2, 0));
    this.mat = new EmissiveMaterial(lightIntensity, lightColor);
    this.lightPos = lightPos;
    this.focalPoint = focalPoint;
    this.lightUp = lightUp;
    this.hasShadowMap = hasShadowMap;
    this.fbo = new FBO(gl);
  }

  CalcLightMVP(translate, scale) {
    const model = mat4.create();
    const view = mat4.create();
    const projection = mat4.create();
    const mvp = mat4.create();
    // Model: translate, then scale, as MeshRender places the object.
    mat4.translate(model, model, translate);
    mat4.scale(model, model, scale);
    mat4.lookAt(view, this.lightPos, this.focalPoint, this.lightUp);
    const halfWidth = 100;
    mat4.ortho(projection, -halfWidth, halfWidth, -halfWidth, halfWidth, 0.01, 400);
    mat4.multiply(mvp, projection, view);
    mat4.multiply(mvp, mvp, model);
    return mvp;
  }
}
