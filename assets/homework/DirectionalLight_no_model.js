// Mistake: CalcLightMVP never applies the object's translation and scale, so every object is drawn
// into the map, and looked up, where its model file puts it: at the origin, unscaled. Expected
// finding: light_model_matrix.
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
    mat4.lookAt(view, this.lightPos, this.focalPoint, this.lightUp);
    const halfWidth = 100;
    mat4.ortho(projection, -halfWidth, halfWidth, -halfWidth, halfWidth, 0.01, 400);
    mat4.multiply(mvp, projection, view);
    mat4.multiply(mvp, mvp, model);
    return mvp;
  }
}
