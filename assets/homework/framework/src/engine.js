// shadowlab's own copy of the framework's interface: the canvas and its WebGL context, the camera,
// one directional light at (0, 80, 80) looking at the origin, the two Marry models and the floor,
// and the frame loop.
const cameraPosition = [30, 30, 30];

GAMES202Main();

function GAMES202Main() {
    const canvas = document.querySelector('#glcanvas');
    canvas.width = window.screen.width;
    canvas.height = window.screen.height;
    const gl = canvas.getContext('webgl');
    if (!gl) {
        alert('Unable to initialize WebGL. Your browser or machine may not support it.');
        return;
    }

    const camera = new THREE.PerspectiveCamera(75, gl.canvas.clientWidth / gl.canvas.clientHeight, 1e-2, 1000);
    camera.position.set(cameraPosition[0], cameraPosition[1], cameraPosition[2]);
    const cameraControls = new THREE.OrbitControls(camera, canvas);
    cameraControls.target.set(0, 0, 0);

    const renderer = new WebGLRenderer(gl, camera);
    const lightPos = [0, 80, 80];
    const focalPoint = [0, 0, 0];
    const lightUp = [0, 1, 0];
    const directionLight = new DirectionalLight(5000, [1, 1, 1], lightPos, focalPoint, lightUp, true, renderer.gl);
    renderer.addLight(directionLight);

    const floorTransform = setTransform(0, 0, -30, 4, 4, 4);
    const obj1Transform = setTransform(0, 0, 0, 20, 20, 20);
    const obj2Transform = setTransform(40, 0, -40, 10, 10, 10);
    loadOBJ(renderer, 'assets/mary/', 'Marry', 'PhongMaterial', obj1Transform);
    loadOBJ(renderer, 'assets/mary/', 'Marry', 'PhongMaterial', obj2Transform);
    loadOBJ(renderer, 'assets/floor/', 'floor', 'PhongMaterial', floorTransform);

    function mainLoop() {
        cameraControls.update();
        renderer.render();
        requestAnimationFrame(mainLoop);
    }
    requestAnimationFrame(mainLoop);
}

function setTransform(t_x, t_y, t_z, s_x, s_y, s_z) {
    return {
        modelTransX: t_x,
        modelTransY: t_y,
        modelTransZ: t_z,
        modelScaleX: s_x,
        modelScaleY: s_y,
        modelScaleZ: s_z,
    };
}
