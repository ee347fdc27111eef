// The page `baker view` writes: a volume over its glTF scene, one sphere per probe shaded per
// pixel by the volume's irradiance for that pixel's normal (the GLSL port of the decoders),
// slices of the irradiance for a chosen normal, probe states, relocations, sky visibility, an
// exposure with its colour bar, and a click that prints what `baker sample` would at that point.
//
// What is shown, per pixel: sRGB(clamp(E(n)/π · exposure, 0, 1)) for irradiance (what a white
// Lambertian surface would reflect), sRGB(clamp(V(n), 0, 1)) for sky visibility.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { BasisDecoder, blendProbes, probeNeighbourhood } from '../../decoders/baker_irradiance.js';
import { BAKER_IRRADIANCE_GLSL, bakerUniforms, probeTexture } from '../../decoders/baker_irradiance_webgl.js';

const MODE_IRRADIANCE = 0, MODE_STATES = 1, MODE_VISIBILITY = 2;
// Probe states 0 (inside geometry, filled from neighbours), 1 (valid), 2 (relocated), in sRGB.
const STATE_COLOURS = [ [ 0xea, 0x43, 0x35 ], [ 0x34, 0xa8, 0x53 ], [ 0xfb, 0xbc, 0x04 ] ];
const AXES = { '+X': [ 1, 0, 0 ], '-X': [ - 1, 0, 0 ], '+Y': [ 0, 1, 0 ], '-Y': [ 0, - 1, 0 ], '+Z': [ 0, 0, 1 ], '-Z': [ 0, 0, - 1 ] };

const $ = ( id ) => document.getElementById( id );

function linearToSrgb( v ) {
	const c = Math.min( Math.max( v, 0 ), 1 );
	return c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow( c, 1 / 2.4 ) - 0.055;
}

async function loadVolume() {
	const answer = await fetch( 'volume.json' );
	if ( ! answer.ok ) throw new Error( `volume.json: ${ answer.status }` );
	const info = await answer.json();
	const response = await fetch( info.binary.file );
	if ( ! response.ok ) throw new Error( `${ info.binary.file }: ${ response.status }` );
	const bytes = await response.arrayBuffer();
	const section = ( name, Type ) => new Type( bytes, info.binary.sections[ name ].byte_offset, info.binary.sections[ name ].count );
	const set = info.reconstruction.function_sets[ 0 ];
	const decoder = new BasisDecoder( info.basis, set.sharpness ?? 0 );
	if ( ! decoder.valid ) throw new Error( `basis ${ info.basis } is not one this page decodes` );
	if ( set.type === 'spherical-gaussians' ) decoder.setLobeAxes( set.axes );
	return {
		info, decoder,
		coefficients: section( 'coefficients', Float32Array ),
		visibility: section( 'visibility', Float32Array ),
		states: section( 'states', Int32Array ),
		offsets: section( 'offsets', Float32Array ),
		probeCount: info.dims[ 0 ] * info.dims[ 1 ] * info.dims[ 2 ],
	};
}

function probePosition( info, p ) {
	const [ nx, ny ] = info.dims;
	const ijk = [ p % nx, Math.floor( p / nx ) % ny, Math.floor( p / ( nx * ny ) ) ];
	return new THREE.Vector3( ...ijk.map( ( i, a ) => info.origin[ a ] + info.spacing * i ) );
}

// E(n) and V(n) at a world position, interpolated as `baker sample` does.
function sampleAt( volume, position, normal ) {
	const { info, decoder } = volume;
	const around = probeNeighbourhood( position, info.origin, info.spacing, info.dims );
	const e = decoder.irradiance( blendProbes( volume.coefficients, around, decoder.coefficientsPerProbe ), normal );
	const v = info.visibility_per_probe > 0 ? decoder.visibility( blendProbes( volume.visibility, around, info.visibility_per_probe ), normal ) : null;
	return { irradiance: e, visibility: v };
}

function probeMaterial( volume, renderer ) {
	const texture = probeTexture( volume.coefficients, volume.info.visibility_per_probe > 0 ? volume.visibility : null, volume.decoder, volume.probeCount );
	const limit = renderer.capabilities.maxTextureSize;
	if ( texture.height > limit ) throw new Error( `the probes need a ${ texture.width } × ${ texture.height } texture; this browser's WebGL takes ${ limit } rows` );
	const data = new THREE.DataTexture( texture.data, texture.width, texture.height, THREE.RGBAFormat, THREE.FloatType );
	data.needsUpdate = true;
	const uniforms = { bakerProbes: { value: data }, mode: { value: MODE_IRRADIANCE }, exposure: { value: 1 } };
	for ( const [ name, { value } ] of Object.entries( bakerUniforms( volume.decoder, texture ) ) ) {
		uniforms[ name ] = { value: value instanceof Float32Array ? Array.from( { length: value.length / 3 }, ( _, i ) => new THREE.Vector3( value[ 3 * i ], value[ 3 * i + 1 ], value[ 3 * i + 2 ] ) ) : value };
	}
	const states = STATE_COLOURS.map( ( c ) => `vec3(${ c.map( ( x ) => ( x / 255 ).toFixed( 6 ) ).join( ', ' ) })` ).join( ', ' );
	return new THREE.ShaderMaterial( {
		glslVersion: THREE.GLSL3,
		uniforms,
		vertexShader: /* glsl */ `
in float probeState;
out vec3 worldNormal;
flat out int probe;
flat out int state;
void main() {
  probe = gl_InstanceID;  // instance p is probe p
  state = int( probeState + 0.5 );
  mat4 world = modelMatrix * instanceMatrix;
  worldNormal = mat3( world ) * normal;
  gl_Position = projectionMatrix * viewMatrix * world * vec4( position, 1.0 );
}`,
		fragmentShader: /* glsl */ `
precision highp int;
${ BAKER_IRRADIANCE_GLSL }
uniform int mode;
uniform float exposure;
in vec3 worldNormal;
flat in int probe;
flat in int state;
out vec4 fragColour;
const vec3 STATE_COLOURS[3] = vec3[3]( ${ states } );
vec3 toSrgb( vec3 c ) {
  c = clamp( c, 0.0, 1.0 );
  return mix( 1.055 * pow( c, vec3( 1.0 / 2.4 ) ) - 0.055, 12.92 * c, vec3( lessThanEqual( c, vec3( 0.0031308 ) ) ) );
}
void main() {
  vec3 n = normalize( worldNormal );
  vec3 colour;
  if ( mode == ${ MODE_STATES } ) colour = STATE_COLOURS[ clamp( state, 0, 2 ) ];
  else if ( mode == ${ MODE_VISIBILITY } ) colour = toSrgb( vec3( bakerVisibility( probe, n ) ) );
  else colour = toSrgb( bakerIrradiance( probe, n ) / 3.14159265358979 * exposure );
  fragColour = vec4( colour, 1.0 );
}`,
	} );
}

function probeSpheres( volume, renderer ) {
	const { info } = volume;
	const radius = 0.12 * info.spacing;
	const mesh = new THREE.InstancedMesh( new THREE.SphereGeometry( radius, 64, 32 ), probeMaterial( volume, renderer ), volume.probeCount );
	const state = new Float32Array( volume.probeCount );
	const matrix = new THREE.Matrix4();
	for ( let p = 0; p < volume.probeCount; ++ p ) {
		mesh.setMatrixAt( p, matrix.makeTranslation( probePosition( info, p ) ) );
		state[ p ] = volume.states[ p ];
	}
	mesh.geometry.setAttribute( 'probeState', new THREE.InstancedBufferAttribute( state, 1 ) );
	mesh.computeBoundingSphere();
	mesh.userData.radius = radius;
	return mesh;
}

// Arrows from each relocated probe's grid position to where its light was gathered.
function relocationArrows( volume ) {
	const group = new THREE.Group();
	for ( let p = 0; p < volume.probeCount; ++ p ) {
		if ( volume.states[ p ] !== 2 ) continue;
		const offset = new THREE.Vector3( ...volume.offsets.subarray( 3 * p, 3 * p + 3 ) );
		const length = offset.length();
		if ( ! ( length > 0 ) ) continue;
		group.add( new THREE.ArrowHelper( offset.clone().normalize(), probePosition( volume.info, p ), length, 0xfbbc04, Math.min( 0.3 * length, 0.1 * volume.info.spacing ), Math.min( 0.2 * length, 0.06 * volume.info.spacing ) ) );
	}
	return group;
}

// A slice through the grid across `axis`, textured with the display of E for the chosen normal.
class Slice {
	constructor( volume, axis ) {
		this.volume = volume;
		this.axis = axis;
		const { info } = volume;
		this.inPlane = [ 0, 1, 2 ].filter( ( a ) => a !== axis );
		this.lo = info.origin.slice();
		this.hi = info.origin.map( ( o, a ) => o + info.spacing * Math.max( info.dims[ a ] - 1, 1e-3 ) );
		this.size = this.inPlane.map( ( a ) => Math.min( 256, Math.max( 2, 4 * ( info.dims[ a ] - 1 ) + 1 ) ) );
		const pixels = new Uint8Array( 4 * this.size[ 0 ] * this.size[ 1 ] );
		this.texture = new THREE.DataTexture( pixels, this.size[ 0 ], this.size[ 1 ], THREE.RGBAFormat );
		this.texture.colorSpace = THREE.SRGBColorSpace;
		this.texture.magFilter = THREE.LinearFilter;
		const geometry = new THREE.BufferGeometry();
		geometry.setAttribute( 'position', new THREE.BufferAttribute( new Float32Array( 12 ), 3 ) );
		geometry.setAttribute( 'uv', new THREE.BufferAttribute( new Float32Array( [ 0, 0, 1, 0, 1, 1, 0, 1 ] ), 2 ) );
		geometry.setIndex( [ 0, 1, 2, 0, 2, 3 ] );
		this.mesh = new THREE.Mesh( geometry, new THREE.MeshBasicMaterial( { map: this.texture, side: THREE.DoubleSide, toneMapped: false } ) );
	}

	update( fraction, normal, exposure, visibilityMode ) {
		const [ u, v ] = this.inPlane, a = this.axis;
		const at = this.lo[ a ] + fraction * ( this.hi[ a ] - this.lo[ a ] );
		const corner = ( su, sv ) => { const p = [ 0, 0, 0 ]; p[ a ] = at; p[ u ] = su ? this.hi[ u ] : this.lo[ u ]; p[ v ] = sv ? this.hi[ v ] : this.lo[ v ]; return p; };
		const positions = this.mesh.geometry.attributes.position;
		[ corner( 0, 0 ), corner( 1, 0 ), corner( 1, 1 ), corner( 0, 1 ) ].forEach( ( p, i ) => positions.setXYZ( i, ...p ) );
		positions.needsUpdate = true;
		this.mesh.geometry.computeBoundingSphere();
		const [ w, h ] = this.size, pixels = this.texture.image.data;
		for ( let j = 0; j < h; ++ j ) for ( let i = 0; i < w; ++ i ) {
			const p = [ 0, 0, 0 ];
			p[ a ] = at;
			p[ u ] = this.lo[ u ] + ( i / ( w - 1 ) ) * ( this.hi[ u ] - this.lo[ u ] );
			p[ v ] = this.lo[ v ] + ( j / ( h - 1 ) ) * ( this.hi[ v ] - this.lo[ v ] );
			const s = sampleAt( this.volume, p, normal );
			const shown = visibilityMode && s.visibility !== null ? [ s.visibility, s.visibility, s.visibility ] : s.irradiance.map( ( e ) => e / Math.PI * exposure );
			const at4 = 4 * ( j * w + i );
			for ( let c = 0; c < 3; ++ c ) pixels[ at4 + c ] = Math.round( 255 * linearToSrgb( shown[ c ] ) );
			pixels[ at4 + 3 ] = 255;
		}
		this.texture.needsUpdate = true;
	}
}

// An exposure that puts the brighter probes (95th percentile of E/π over the six axes) at 0.8.
function initialExposure( volume ) {
	const values = [];
	const step = Math.max( 1, Math.floor( volume.probeCount / 4096 ) );
	for ( let p = 0; p < volume.probeCount; p += step ) {
		if ( volume.states[ p ] === 0 ) continue;
		for ( const n of Object.values( AXES ) ) values.push( Math.max( ...volume.decoder.irradiance( volume.coefficients, n, p * volume.decoder.coefficientsPerProbe ) ) / Math.PI );
	}
	values.sort( ( x, y ) => x - y );
	const bright = values.length ? values[ Math.floor( 0.95 * ( values.length - 1 ) ) ] : 1;
	return bright > 0 ? Math.round( 10 * Math.log2( 0.8 / bright ) ) / 10 : 0;
}

async function loadScene( url, scene ) {
	if ( ! url ) return null;
	const gltf = await new GLTFLoader().loadAsync( url );
	scene.add( gltf.scene );
	return gltf.scene;
}

async function main() {
	const volume = await loadVolume();
	const { info } = volume;
	const canvas = $( 'view' );
	const renderer = new THREE.WebGLRenderer( { canvas, antialias: true, preserveDrawingBuffer: true } );
	renderer.setPixelRatio( window.devicePixelRatio );
	renderer.setSize( canvas.clientWidth, canvas.clientHeight, false );
	renderer.toneMapping = THREE.NoToneMapping;
	const scene = new THREE.Scene();
	scene.background = new THREE.Color( 0x202124 );
	scene.add( new THREE.HemisphereLight( 0xffffff, 0x444444, 1.5 ) );
	const sun = new THREE.DirectionalLight( 0xffffff, 1.0 );
	sun.position.set( 1, 2, 1.5 );
	scene.add( sun );

	const centre = new THREE.Vector3( ...info.origin.map( ( o, a ) => o + 0.5 * info.spacing * ( info.dims[ a ] - 1 ) ) );
	const extent = Math.max( ...info.dims ) * info.spacing;
	const camera = new THREE.PerspectiveCamera( 50, canvas.clientWidth / canvas.clientHeight, extent * 1e-3, extent * 20 );
	camera.position.copy( centre ).add( new THREE.Vector3( 0.9, 0.7, 1.2 ).multiplyScalar( extent ) );
	const controls = new OrbitControls( camera, canvas );
	controls.target.copy( centre );
	controls.update();

	const probes = probeSpheres( volume, renderer );
	scene.add( probes );
	const arrows = relocationArrows( volume );
	scene.add( arrows );
	const slices = [ 0, 1, 2 ].map( ( axis ) => new Slice( volume, axis ) );
	slices.forEach( ( s ) => scene.add( s.mesh ) );
	const gltfScene = await loadScene( info.scene, scene );

	$( 'title' ).textContent = `${ info.volume }: ${ info.basis }`;
	$( 'summary' ).textContent = `${ info.dims.join( ' × ' ) } probes, spacing ${ info.spacing } m; ` +
		`${ volume.states.filter( ( s ) => s === 2 ).length } relocated, ${ volume.states.filter( ( s ) => s === 0 ).length } filled` +
		( info.scene ? '' : '; no scene (baker view --gltf)' );
	$( 'levels' ).innerHTML = info.levels.map( ( l ) => `<label><input type="checkbox" class="level" data-level="${ l.level }" checked> level ${ l.level } (spacing ${ l.spacing } m)</label>` ).join( '' );
	for ( const name of Object.keys( AXES ) ) $( 'slice-normal' ).add( new Option( name, name, name === '+Y', name === '+Y' ) );
	$( 'exposure' ).value = initialExposure( volume );
	if ( info.visibility_per_probe === 0 ) $( 'show-visibility' ).disabled = true;

	const settings = () => ( {
		exposure: Math.pow( 2, Number( $( 'exposure' ).value ) ),
		mode: $( 'show-states' ).checked ? MODE_STATES : $( 'show-visibility' ).checked ? MODE_VISIBILITY : MODE_IRRADIANCE,
	} );
	function refresh() {
		const { exposure, mode } = settings();
		probes.material.uniforms.exposure.value = exposure;
		probes.material.uniforms.mode.value = mode;
		probes.visible = $( 'show-probes' ).checked && [ ...document.querySelectorAll( '.level' ) ].some( ( l ) => l.checked );
		arrows.visible = $( 'show-offsets' ).checked;
		if ( gltfScene ) gltfScene.visible = $( 'show-scene' ).checked;
		const visibilityMode = mode === MODE_VISIBILITY;
		slices.forEach( ( s, a ) => {
			s.mesh.visible = $( `slice-${ 'xyz'[ a ] }` ).checked;
			if ( s.mesh.visible ) s.update( Number( $( `slice-${ 'xyz'[ a ] }-at` ).value ) / 1000, AXES[ $( 'slice-normal' ).value ], exposure, visibilityMode );
		} );
		$( 'exposure-value' ).textContent = `${ Number( $( 'exposure' ).value ).toFixed( 1 ) } stops (×${ exposure.toPrecision( 3 ) })`;
		drawColourBar( exposure, visibilityMode );
	}
	function drawColourBar( exposure, visibilityMode ) {
		const bar = $( 'colourbar' ), context = bar.getContext( '2d' );
		for ( let x = 0; x < bar.width; ++ x ) {
			const g = Math.round( 255 * linearToSrgb( x / ( bar.width - 1 ) ) );
			context.fillStyle = `rgb(${ g },${ g },${ g })`;
			context.fillRect( x, 0, 1, bar.height );
		}
		const top = visibilityMode ? 1 : Math.PI / exposure;
		$( 'ticks' ).innerHTML = [ 0, 0.25, 0.5, 0.75, 1 ].map( ( f ) => `<span>${ ( f * top ).toPrecision( 3 ) }</span>` ).join( '' );
		$( 'units' ).textContent = visibilityMode ? 'sky visibility V(n): 1 under open sky' : `E(n): ${ info.units }; white where E/π · exposure reaches 1`;
	}
	// Slices are decoded on the CPU: at most once a frame however fast a slider moves.
	let pending = false;
	const scheduleRefresh = () => {
		if ( pending ) return;
		pending = true;
		requestAnimationFrame( () => { pending = false; refresh(); } );
	};
	document.querySelectorAll( '#panel input, #panel select' ).forEach( ( e ) => e.addEventListener( 'input', scheduleRefresh ) );
	refresh();

	// A click (not a drag) prints the point and its irradiance for the six axis normals.
	const raycaster = new THREE.Raycaster();
	let down = null;
	canvas.addEventListener( 'pointerdown', ( e ) => { down = [ e.clientX, e.clientY ]; } );
	canvas.addEventListener( 'pointerup', ( e ) => {
		if ( ! down || Math.hypot( e.clientX - down[ 0 ], e.clientY - down[ 1 ] ) > 4 ) return;
		const rect = canvas.getBoundingClientRect();
		raycaster.setFromCamera( new THREE.Vector2( ( e.clientX - rect.left ) / rect.width * 2 - 1, - ( ( e.clientY - rect.top ) / rect.height ) * 2 + 1 ), camera );
		const targets = [ probes, ...slices.map( ( s ) => s.mesh ), ...( gltfScene ? [ gltfScene ] : [] ) ].filter( ( o ) => o.visible );
		const hit = raycaster.intersectObjects( targets, true )[ 0 ];
		if ( hit ) pick( hit.point.toArray() );
	} );
	function pick( position ) {
		const lines = [ `position (${ position.map( ( x ) => x.toFixed( 4 ) ).join( ', ' ) })` ];
		const result = { position, irradiance: {} };
		for ( const [ name, n ] of Object.entries( AXES ) ) {
			const s = sampleAt( volume, position, n );
			result.irradiance[ name ] = s.irradiance;
			lines.push( `${ name }  E = (${ s.irradiance.map( ( x ) => x.toPrecision( 6 ) ).join( ', ' ) })` );
		}
		$( 'picked' ).textContent = lines.join( '\n' );
		console.log( JSON.stringify( result ) );
		return result;
	}

	function render() {
		renderer.render( scene, camera );
	}
	renderer.setAnimationLoop( () => {
		controls.update();
		render();
	} );
	window.addEventListener( 'resize', () => {
		renderer.setSize( canvas.clientWidth, canvas.clientHeight, false );
		camera.aspect = canvas.clientWidth / canvas.clientHeight;
		camera.updateProjectionMatrix();
	} );

	// For tests and scripts: the colours of the four pixels around the centre of probe (i, j, k)'s
	// sphere seen from `towards` (its normal there; the centre is their common corner, so their
	// mean is the colour there to second order), with only the probes drawn; and pick() as a click does.
	window.viewer = {
		info,
		pick,
		resetExposure() {
			$( 'exposure' ).value = initialExposure( volume );
			refresh();
		},
		setOption( id, value ) {
			const e = $( id );
			if ( e.type === 'checkbox' ) e.checked = value;
			else e.value = String( value );
			refresh();
		},
		captureProbe( ijk, towards ) {
			const p = ijk[ 0 ] + info.dims[ 0 ] * ( ijk[ 1 ] + info.dims[ 1 ] * ijk[ 2 ] );
			const at = probePosition( info, p ), n = new THREE.Vector3( ...towards ).normalize();
			const saved = { position: camera.position.clone(), target: controls.target.clone() };
			const hidden = [ arrows, ...slices.map( ( s ) => s.mesh ), ...( gltfScene ? [ gltfScene ] : [] ) ].filter( ( o ) => o.visible );
			hidden.forEach( ( o ) => { o.visible = false; } );
			camera.position.copy( at ).addScaledVector( n, 6 * probes.userData.radius );
			camera.lookAt( at );
			render();
			const gl = renderer.getContext(), block = new Uint8Array( 16 );
			gl.readPixels( gl.drawingBufferWidth / 2 - 1, gl.drawingBufferHeight / 2 - 1, 2, 2, gl.RGBA, gl.UNSIGNED_BYTE, block );
			hidden.forEach( ( o ) => { o.visible = true; } );
			camera.position.copy( saved.position );
			controls.target.copy( saved.target );
			camera.lookAt( saved.target );
			const pixels = [ 0, 1, 2, 3 ].map( ( i ) => Array.from( block.slice( 4 * i, 4 * i + 3 ) ) );
			return { pixels, position: at.toArray(), normal: n.toArray(), exposure: settings().exposure };
		},
	};
	window.viewerReady = true;
}

main().catch( ( error ) => {
	console.error( error );
	$( 'summary' ).textContent = `cannot show the volume: ${ error.message }`;
} );
