// shadowlab's own copy of the framework's interface: an object's colour texture.
class Texture {
    constructor() {}

    CreateImageTexture(gl, image) {
        this.texture = gl.createTexture();
        this.image = image;
    }

    CreateConstantTexture(gl, buffer) {
        this.texture = gl.createTexture();
        this.color = buffer;
    }
}
