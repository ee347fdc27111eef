// The three.js export loaded by three.js r187 itself (the pinned npm three) in headless Chromium:
// a white Lambertian sphere at a probe, lit by nothing but the loaded LightProbeGridWebGL. Each
// chosen pixel, after undoing the page's known output transform (linear tone mapping at a given
// exposure, then sRGB), must equal baker sample's irradiance over π within 2 %, where three.js
// looks the grid up: the shaded point pushed half a cell along its normal.
import fs from 'node:fs';
import path from 'node:path';
import { bake, check, finish, freshDirectory, runBaker, sample, sourceDir } from './support.mjs';
import { nodeModules, openPage, serve } from './browser.mjs';

const scene = path.join( sourceDir, 'data/default_room/default_room.gltf' );
const dir = freshDirectory( 'threejs' );
const SIZE = 256; // canvas pixels; the sphere's radius spans SIZE / 2.5 of them
const TOLERANCE = 0.02;

const page = `<!doctype html><html><body style="margin:0">
<canvas id="view" width="${ SIZE }" height="${ SIZE }"></canvas>
<script type="importmap">{ "imports": { "three": "/node_modules/three/build/three.module.js",
  "three/addons/": "/node_modules/three/examples/jsm/" } }</script>
<script type="module">
import * as THREE from 'three';
import { loadBakerLightProbeGrid } from '/decoders/three/bakerLightProbeGrid.js';
const renderer = new THREE.WebGLRenderer( { canvas: document.getElementById( 'view' ), preserveDrawingBuffer: true } );
renderer.setPixelRatio( 1 );
renderer.setSize( ${ SIZE }, ${ SIZE }, false );
renderer.toneMapping = THREE.LinearToneMapping;
renderer.outputColorSpace = THREE.SRGBColorSpace;
const grid = await loadBakerLightProbeGrid( '/volume/' );
// Bytes of the given pixels (x from the left, y from the bottom) of a white Lambertian sphere.
window.renderSphere = ( { centre, radius, exposure, pixels } ) => {
  const scene = new THREE.Scene();
  scene.add( grid );
  const sphere = new THREE.Mesh( new THREE.SphereGeometry( radius, 512, 256 ), new THREE.MeshLambertMaterial( { color: 0xffffff } ) );
  sphere.position.fromArray( centre );
  scene.add( sphere );
  const half = 1.25 * radius;
  const camera = new THREE.OrthographicCamera( - half, half, half, - half, radius, 10 * radius );
  camera.position.set( centre[ 0 ], centre[ 1 ], centre[ 2 ] + 4 * radius );
  camera.lookAt( ...centre );
  renderer.toneMappingExposure = exposure;
  renderer.render( scene, camera );
  const gl = renderer.getContext(), bytes = new Uint8Array( 4 );
  return pixels.map( ( [ x, y ] ) => { gl.readPixels( x, y, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, bytes ); return Array.from( bytes ); } );
};
window.ready = true;
</script></body></html>`;

function srgbToLinear( byte ) {
	const v = byte / 255;
	return v <= 0.04045 ? v / 12.92 : Math.pow( ( v + 0.055 ) / 1.055, 2.4 );
}

// The pixel nearest where the sphere's normal is `wanted`, and the normal at that pixel's centre
// (the camera is orthographic, looking down −z at the sphere's centre).
function pixelFor( wanted, radius ) {
	const half = 1.25 * radius, perPixel = 2 * half / SIZE;
	const px = Math.floor( SIZE / 2 + wanted[ 0 ] * radius / perPixel ), py = Math.floor( SIZE / 2 + wanted[ 1 ] * radius / perPixel );
	const nx = ( ( px + 0.5 ) * perPixel - half ) / radius, ny = ( ( py + 0.5 ) * perPixel - half ) / radius;
	return { pixel: [ px, py ], normal: [ nx, ny, Math.sqrt( 1 - nx * nx - ny * ny ) ] };
}

const common = [ scene, '--basis', 'sh-l2', '--rays', '256', '--spacing', '1', '--seed', '2' ];
const summary = bake( [ ...common, '--format', 'threejs', '--out', 'room_threejs' ], dir );
bake( [ ...common, '--out', 'room.vdb' ], dir );
check( summary.format === 'threejs' && summary.engine_export.clamped_values === 0, 'threejs summary' );
const exportDir = path.join( dir, 'room_threejs' );
const json = JSON.parse( fs.readFileSync( path.join( exportDir, 'light_probe_grid.json' ), 'utf8' ) );
const [ nx, ny, nz ] = json.resolution;
const cell = json.width / nx;

// The JSON (PR #33658's integers) and the atlas hold the same radiance: the atlas as halves, its
// padding layers copies of the first and last slice.
function halfToFloat( h ) {
	const exponent = ( h >> 10 ) & 0x1f, mantissa = h & 0x3ff, sign = h & 0x8000 ? - 1 : 1;
	if ( exponent === 0 ) return sign * mantissa * Math.pow( 2, - 24 );
	return sign * ( 1 + mantissa / 1024 ) * Math.pow( 2, exponent - 15 );
}
const atlasBytes = fs.readFileSync( path.join( exportDir, 'light_probe_grid.bin' ) );
const atlas = new DataView( atlasBytes.buffer, atlasBytes.byteOffset, atlasBytes.byteLength );
check( atlasBytes.byteLength === nx * ny * 7 * ( nz + 2 ) * 4 * 2, `atlas of ${ atlasBytes.byteLength } bytes` );
let worstAtlas = 0;
for ( let layer = 0; layer < 7 * ( nz + 2 ); ++ layer ) for ( let j = 0; j < ny; ++ j ) for ( let i = 0; i < nx; ++ i ) for ( let c = 0; c < 4; ++ c ) {
	const t = Math.floor( layer / ( nz + 2 ) ), k = Math.min( Math.max( layer % ( nz + 2 ) - 1, 0 ), nz - 1 ), value = 4 * t + c;
	const stored = halfToFloat( atlas.getUint16( 2 * ( ( ( layer * ny + j ) * nx + i ) * 4 + c ), true ) );
	const fromJson = value < 27 ? json.coefficients.data[ ( i + nx * ( j + ny * k ) ) * 27 + value ] / json.coefficients.scale : 0;
	// Half's rounding, the integers' own step and half's subnormal step.
	const allowed = Math.abs( fromJson ) * Math.pow( 2, - 11 ) + 0.5 / json.coefficients.scale + Math.pow( 2, - 25 );
	const error = Math.abs( stored - fromJson ) / allowed;
	worstAtlas = Math.max( worstAtlas, error );
}
check( worstAtlas <= 1.0001, `atlas against JSON: largest difference ${ worstAtlas } of the rounding allowed` );

// A basis three.js cannot hold is refused before baking, naming it and the formats that take it.
const refused = runBaker( [ scene, '--basis', 'ad-ycocg', '--format', 'threejs', '--rays', '16', '--out', 'refused' ], dir );
check( refused.code === 2 && /ad-ycocg/.test( refused.stderr ) && /sh-l2/.test( refused.stderr ) && /bevy/.test( refused.stderr ),
	`refusal: exit ${ refused.code }, ${ refused.stderr.trim() }` );
check( ! fs.existsSync( path.join( dir, 'refused' ) ), 'a refused bake writes nothing' );

const { server, url } = await serve( page, { '/node_modules/': nodeModules( sourceDir ), '/decoders/': path.join( sourceDir, 'decoders' ), '/volume/': exportDir } );
const { browser, page: tab, errors } = await openPage( url );
let worst = 0;
try {
	await tab.waitForFunction( 'window.ready === true || false', { timeout: 60000 } ).catch( () => {} );
	check( await tab.evaluate( () => window.ready === true ), `the page loaded the grid (errors: ${ errors.join( '; ' ) })` );
	const wanted = [ [ 0, 0, 1 ], [ 0.5, 0.45, 0.74 ], [ - 0.62, - 0.35, 0.7 ] ];
	for ( const probe of [ [ 1, 1, 1 ], [ 2, 1, 2 ] ].filter( ( p ) => p[ 0 ] < nx && p[ 1 ] < ny && p[ 2 ] < nz ) ) {
		// three.js r187 puts probe (i, j, k) at the centre of its cell of the box.
		const centre = probe.map( ( i, a ) => json.position[ a ] - 0.5 * cell * json.resolution[ a ] + ( i + 0.5 ) * cell );
		const radius = 0.1 * cell;
		const chosen = wanted.map( ( n ) => pixelFor( n, radius ) );
		const expected = chosen.map( ( { normal } ) => {
			const lookup = centre.map( ( c, a ) => c + radius * normal[ a ] + 0.5 * cell * normal[ a ] );
			return sample( path.join( dir, 'room.vdb' ), lookup, normal ).irradiance.map( ( e ) => Math.max( 0, e ) / Math.PI );
		} );
		const exposure = 0.8 / Math.max( ...expected.flat() );
		const bytes = await tab.evaluate( ( args ) => window.renderSphere( args ), { centre, radius, exposure, pixels: chosen.map( ( c ) => c.pixel ) } );
		chosen.forEach( ( { normal }, n ) => {
			const rendered = bytes[ n ].slice( 0, 3 ).map( ( b ) => srgbToLinear( b ) / exposure );
			const brightest = Math.max( ...expected[ n ] );
			worst = Math.max( worst, ...rendered.map( ( r, c ) => Math.abs( r - expected[ n ][ c ] ) / brightest ) );
			for ( let c = 0; c < 3; ++ c ) {
				const error = Math.abs( rendered[ c ] - expected[ n ][ c ] ) / brightest;
				check( error <= TOLERANCE, `probe ${ probe } normal ${ normal.map( ( v ) => v.toFixed( 3 ) ) } channel ${ c }: ` +
					`rendered ${ rendered[ c ].toFixed( 5 ) }, baker sample ${ expected[ n ][ c ].toFixed( 5 ) }` );
			}
			console.log( `probe ${ probe } normal (${ normal.map( ( v ) => v.toFixed( 3 ) ) }): rendered (${ rendered.map( ( v ) => v.toFixed( 4 ) ) }), ` +
				`baker sample / pi (${ expected[ n ].map( ( v ) => v.toFixed( 4 ) ) })` );
		} );
	}
	check( errors.length === 0, `console errors: ${ errors.join( '; ' ) }` );
	console.log( `largest difference ${ ( 100 * worst ).toFixed( 2 ) } % of the pixel's brightest channel` );
} finally {
	await browser.close();
	server.close();
}
finish( 'three.js render' );
