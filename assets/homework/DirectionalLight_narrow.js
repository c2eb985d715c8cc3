// Mistake: an orthographic box only 50 world units wide, narrower than the scene the camera sees:
// what lies outside it has no shadow map. Expected finding: light_frustum_clips.
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
    const halfWidth = 25;
    mat4.ortho(projection, -halfWidth, halfWidth, -halfWidth, halfWidth, 0.01, 400);
    mat4.multiply(mvp, projection, view);
    mat4.multiply(mvp, mvp, model);
    return mvp;
  }
}
