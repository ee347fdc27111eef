// decoders/baker_irradiance_webgl.js (the GLSL the viewer shades probes with) against
// decoders/baker_irradiance.h: every basis's random coefficients (decoder_samples) decoded per
// pixel in WebGL 2 (Debian's headless Chromium, SwiftShader) into a float render target must
// agree with the header within 1e-5 of max(1, |E|) (the coefficients are at most 1). Then
// adaptive volumes (decoder_samples adaptive): the level each point is read from, through the
// indirection texture, and E and visibility there, against the header's finestLevelNeighbourhood.
// Last, the desktop GLSL's own run-time relighting and leak weight (shaders/baker_irradiance.glsl,
// those sections alone, which keep to what GLSL ES 3.00 shares with 4.50) run in WebGL:
// bakerRelitIrradiance against the library (decoder_samples relit, the rest and visibility
// decoded by the JavaScript decoder) within 1e-5 of max(1, |E|), bakerLeakWeight against the
// header (decoder_samples leak) within 1e-5.
// argv: node decoder_webgl.test.mjs DECODER_SAMPLES SOURCE_DIR
import { execFileSync } from 'node:child_process';
import path from 'node:path';
import { openPage, serve } from './browser.mjs';

const [ samplesBinary, sourceDir ] = process.argv.slice( 2 );
const samples = ( ...args ) => JSON.parse( execFileSync( samplesBinary, args, { encoding: 'utf8', maxBuffer: 1 << 30 } ) );
const bases = samples(), adaptive = samples( 'adaptive' ), relit = samples( 'relit' ), leak = samples( 'leak' );

const page = `<!doctype html><html><body><canvas id="gl"></canvas><script type="module">
import { BasisDecoder } from '/decoders/baker_irradiance.js';
import { BAKER_IRRADIANCE_GLSL, adaptiveGlsl, adaptiveTextures, bakerUniforms, probeTexture } from '/decoders/baker_irradiance_webgl.js';
const gl = document.getElementById( 'gl' ).getContext( 'webgl2' );
if ( ! gl.getExtension( 'EXT_color_buffer_float' ) ) throw new Error( 'no EXT_color_buffer_float' );
function compile( type, source ) {
  const s = gl.createShader( type );
  gl.shaderSource( s, source );
  gl.compileShader( s );
  if ( ! gl.getShaderParameter( s, gl.COMPILE_STATUS ) ) throw new Error( gl.getShaderInfoLog( s ) );
  return s;
}
function link( declarations, main, prelude = BAKER_IRRADIANCE_GLSL ) {
  const program = gl.createProgram();
  gl.attachShader( program, compile( gl.VERTEX_SHADER, '#version 300 es\\nvoid main() { vec2 p = vec2( gl_VertexID & 1, gl_VertexID >> 1 ) * 4.0 - 1.0; gl_Position = vec4( p, 0, 1 ); }' ) );
  gl.attachShader( program, compile( gl.FRAGMENT_SHADER, '#version 300 es\\nprecision highp float;\\nprecision highp int;\\n' + prelude + declarations +
    '\\nuniform highp sampler2D directions;\\nout vec4 colour;\\nvoid main() { int p = int( gl_FragCoord.x ); vec3 n = texelFetch( directions, ivec2( p, 0 ), 0 ).xyz;' + main + ' }' ) );
  gl.linkProgram( program );
  if ( ! gl.getProgramParameter( program, gl.LINK_STATUS ) ) throw new Error( gl.getProgramInfoLog( program ) );
  return program;
}
const program = link( '', ' colour = vec4( bakerIrradiance( p, n ), bakerVisibility( p, n ) );' );
const adaptiveProgram = link( await adaptiveGlsl(), ' vec3 at = texelFetch( directions, ivec2( p, 1 ), 0 ).xyz;' +
  ' colour = vec4( bakerAdaptiveIrradiance( at, n ), bakerAdaptiveVisibility( at, n ) );' );
const desktop = await ( await fetch( '/shaders/baker_irradiance.glsl' ) ).text();
function section( from, to ) {
  const begin = desktop.indexOf( from ), end = desktop.indexOf( to, begin );
  if ( begin < 0 || end < 0 ) throw new Error( 'baker_irradiance.glsl has no section from "' + from + '" to "' + to + '"' );
  return desktop.slice( begin, end );
}
const relitProgram = link( '', ' vec4 restAndVisibility = texelFetch( directions, ivec2( p, 1 ), 0 ); vec3 sky[9];' +
  ' for ( int i = 0; i < 9; ++ i ) sky[ i ] = texelFetch( directions, ivec2( p, 2 + i ), 0 ).xyz;' +
  ' colour = vec4( bakerRelitIrradiance( restAndVisibility.xyz, restAndVisibility.w, sky, n ), 0.0 );',
  section( '// ---- Real spherical harmonics', '// R, G and B of function i' ) );
const leakProgram = link( '\\nuniform highp sampler2D moments;', ' vec4 probe = texelFetch( directions, ivec2( p, 1 ), 0 );' +
  ' vec4 point = texelFetch( directions, ivec2( p, 2 ), 0 );' +
  ' colour = vec4( bakerLeakWeight( moments, ivec2( 8 * p, 0 ), int( probe.w ), point.w, probe.xyz, point.xyz, n, 1.0 ), 0.0, 0.0, 0.0 );',
  section( '// ---- Leak-aware weights', '// ---- Adaptive volumes' ) );
function floatTexture( unit, width, height, data, format = 'RGBA' ) {
  const t = gl.createTexture();
  gl.activeTexture( gl.TEXTURE0 + unit );
  gl.bindTexture( gl.TEXTURE_2D, t );
  gl.texImage2D( gl.TEXTURE_2D, 0, format === 'RG' ? gl.RG32F : gl.RGBA32F, width, height, 0, gl[ format ], gl.FLOAT, data );
  gl.texParameteri( gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST );
  gl.texParameteri( gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST );
  return t;
}
function setUniforms( program, uniforms ) {
  for ( const [ name, { type, value } ] of Object.entries( uniforms ) ) {
    const at = gl.getUniformLocation( program, name );
    if ( type === 'vec3[]' ) gl.uniform3fv( at, value );
    else if ( type === 'ivec3[]' ) gl.uniform3iv( at, value );
    else if ( type === 'int[]' ) gl.uniform1iv( at, value );
    else if ( type === 'float[]' ) gl.uniform1fv( at, value );
    else if ( type === 'int' ) gl.uniform1i( at, value );
    else gl.uniform1f( at, value );
  }
}
// Draws n pixels of the bound program into a float target and reads them back.
function render( n ) {
  const target = gl.createTexture();
  gl.activeTexture( gl.TEXTURE3 );
  gl.bindTexture( gl.TEXTURE_2D, target );
  gl.texStorage2D( gl.TEXTURE_2D, 1, gl.RGBA32F, n, 1 );
  const framebuffer = gl.createFramebuffer();
  gl.bindFramebuffer( gl.FRAMEBUFFER, framebuffer );
  gl.framebufferTexture2D( gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, target, 0 );
  gl.viewport( 0, 0, n, 1 );
  gl.drawArrays( gl.TRIANGLES, 0, 3 );
  const out = new Float32Array( 4 * n );
  gl.readPixels( 0, 0, n, 1, gl.RGBA, gl.FLOAT, out );
  return Array.from( out );
}
window.decode = ( entry ) => {
  const decoder = new BasisDecoder( entry.basis, entry.sharpness ?? 0 );
  if ( entry.axes ) decoder.setLobeAxes( entry.axes );
  const n = entry.cases.length, perProbe = decoder.coefficientsPerProbe, count0 = decoder.coefficientCount( 0 );
  const coefficients = new Float32Array( n * perProbe ), visibility = new Float32Array( n * count0 ), directions = new Float32Array( 4 * n );
  entry.cases.forEach( ( c, p ) => {
    coefficients.set( c.coefficients, p * perProbe );
    visibility.set( c.coefficients.slice( 0, count0 ), p * count0 );
    directions.set( c.direction, 4 * p );
  } );
  const probes = probeTexture( coefficients, visibility, decoder, n );
  gl.useProgram( program );
  floatTexture( 0, probes.width, probes.height, probes.data );
  floatTexture( 1, n, 1, directions );
  gl.uniform1i( gl.getUniformLocation( program, 'bakerProbes' ), 0 );
  gl.uniform1i( gl.getUniformLocation( program, 'directions' ), 1 );
  setUniforms( program, bakerUniforms( decoder, probes ) );
  return render( n );
};
window.decodeAdaptive = ( entry ) => {
  const decoder = new BasisDecoder( entry.basis, 0 );
  const levels = entry.levels.map( ( l ) => ( { ...l, coefficients: new Float32Array( l.coefficients ), visibility: new Float32Array( l.visibility ) } ) );
  const pool = adaptiveTextures( levels, decoder );
  const n = entry.points.length, rows = new Float32Array( 8 * n );
  entry.points.forEach( ( point, p ) => {
    rows.set( point.normal, 4 * p );
    rows.set( point.position, 4 * ( n + p ) );
  } );
  gl.useProgram( adaptiveProgram );
  floatTexture( 0, pool.probes.width, pool.probes.height, pool.probes.data );
  floatTexture( 1, n, 2, rows );
  const indirection = gl.createTexture();
  gl.activeTexture( gl.TEXTURE2 );
  gl.bindTexture( gl.TEXTURE_3D, indirection );
  gl.texImage3D( gl.TEXTURE_3D, 0, gl.R32UI, pool.indirection.width, pool.indirection.height, pool.indirection.depth, 0, gl.RED_INTEGER, gl.UNSIGNED_INT, pool.indirection.data );
  gl.texParameteri( gl.TEXTURE_3D, gl.TEXTURE_MIN_FILTER, gl.NEAREST );
  gl.texParameteri( gl.TEXTURE_3D, gl.TEXTURE_MAG_FILTER, gl.NEAREST );
  gl.uniform1i( gl.getUniformLocation( adaptiveProgram, 'bakerProbes' ), 0 );
  gl.uniform1i( gl.getUniformLocation( adaptiveProgram, 'directions' ), 1 );
  gl.uniform1i( gl.getUniformLocation( adaptiveProgram, 'bakerIndirection' ), 2 );
  setUniforms( adaptiveProgram, { ...bakerUniforms( decoder, pool.probes ), ...pool.uniforms } );
  return render( n );
};
// Every basis's relit cases, a pixel each: row 0 the normal, row 1 the rest's E and V from the
// JavaScript decoder, rows 2-10 the sky's nine RGB coefficients.
window.decodeRelit = ( entries ) => {
  const cases = [];
  for ( const entry of entries ) {
    const decoder = new BasisDecoder( entry.basis, entry.sharpness ?? 0 );
    if ( entry.axes ) decoder.setLobeAxes( entry.axes );
    for ( const c of entry.cases ) cases.push( { c, e: decoder.irradiance( c.rest, c.normal ), v: decoder.visibility( c.visibility, c.normal ) } );
  }
  const n = cases.length, rows = new Float32Array( 4 * n * 11 );
  cases.forEach( ( { c, e, v }, p ) => {
    rows.set( c.normal, 4 * p );
    rows.set( [ ...e, v ], 4 * ( n + p ) );
    for ( let i = 0; i < 9; ++ i ) rows.set( [ c.sky[ i ], c.sky[ 9 + i ], c.sky[ 18 + i ] ], 4 * ( ( 2 + i ) * n + p ) );
  } );
  gl.useProgram( relitProgram );
  floatTexture( 1, n, 11, rows );
  gl.uniform1i( gl.getUniformLocation( relitProgram, 'directions' ), 1 );
  return render( n );
};
// Each leak case a pixel, its map an 8 × 8 tile of a two-channel texture (a 4 × 4 map in the
// tile's corner): row 0 the normal, row 1 the probe and the map's size, row 2 the point and its cap.
window.leakWeights = ( cases ) => {
  const n = cases.length, tiles = new Float32Array( 2 * 8 * n * 8 ), rows = new Float32Array( 4 * n * 3 );
  cases.forEach( ( c, p ) => {
    const size = c.map.size;
    for ( let t = 0; t < size * size; ++ t ) tiles.set( [ c.moments[ 2 * t ], c.moments[ 2 * t + 1 ] ], 2 * ( ( t / size | 0 ) * 8 * n + 8 * p + t % size ) );
    rows.set( c.normal, 4 * p );
    rows.set( [ ...c.probe, size ], 4 * ( n + p ) );
    rows.set( [ ...c.point, c.map.cap ], 4 * ( 2 * n + p ) );
  } );
  gl.useProgram( leakProgram );
  floatTexture( 0, 8 * n, 8, tiles, 'RG' );
  floatTexture( 1, n, 3, rows );
  gl.uniform1i( gl.getUniformLocation( leakProgram, 'moments' ), 0 );
  gl.uniform1i( gl.getUniformLocation( leakProgram, 'directions' ), 1 );
  return render( n );
};
window.ready = true;
</script></body></html>`;

const { server, url } = await serve( page, { '/decoders/': path.join( sourceDir, 'decoders' ), '/shaders/': path.join( sourceDir, 'shaders' ) } );
const { browser, page: tab, errors } = await openPage( url );
let checks = 0, failures = 0, worst = 0, worstAdaptive = 0, worstRelit = 0, worstLeak = 0, walled = 0;
const fail = ( message ) => { if ( ++ failures <= 20 ) console.error( `FAIL: ${ message }` ); };
try {
	await tab.waitForFunction( 'window.ready === true', { timeout: 60000 } ).catch( () => {} );
	for ( const entry of bases ) {
		const got = await tab.evaluate( ( e ) => window.decode( e ), entry );
		entry.cases.forEach( ( c, p ) => {
			const expected = [ ...c.irradiance, c.visibility ];
			for ( let k = 0; k < 4; ++ k ) {
				const error = Math.abs( got[ 4 * p + k ] - expected[ k ] ) / Math.max( 1, Math.abs( expected[ k ] ) );
				worst = Math.max( worst, error );
				++ checks;
				if ( ! ( error <= 1e-5 ) ) fail( `${ entry.basis } at ${ c.direction }: value ${ k } ${ got[ 4 * p + k ] }, header ${ expected[ k ] }` );
			}
		} );
	}
	for ( const entry of adaptive ) {
		const got = await tab.evaluate( ( e ) => window.decodeAdaptive( e ), entry );
		entry.points.forEach( ( point, p ) => {
			const expected = [ ...point.irradiance, point.visibility ];
			for ( let k = 0; k < 4; ++ k ) {
				const error = Math.abs( got[ 4 * p + k ] - expected[ k ] ) / Math.max( 1, Math.abs( expected[ k ] ) );
				worstAdaptive = Math.max( worstAdaptive, error );
				++ checks;
				if ( ! ( error <= 1e-5 ) ) fail( `adaptive ${ entry.basis } at ${ point.position } (level ${ point.level }): value ${ k } ${ got[ 4 * p + k ] }, header ${ expected[ k ] }` );
			}
		} );
	}
	const relitGot = await tab.evaluate( ( e ) => window.decodeRelit( e ), relit );
	relit.flatMap( ( entry ) => entry.cases.map( ( c ) => [ entry.basis, c ] ) ).forEach( ( [ basis, c ], p ) => {
		for ( let k = 0; k < 3; ++ k ) {
			const error = Math.abs( relitGot[ 4 * p + k ] - c.irradiance[ k ] ) / Math.max( 1, Math.abs( c.irradiance[ k ] ) );
			worstRelit = Math.max( worstRelit, error );
			++ checks;
			if ( ! ( error <= 1e-5 ) ) fail( `relit ${ basis } at ${ c.normal }: ${ relitGot[ 4 * p + k ] }, library ${ c.irradiance[ k ] }` );
		}
	} );
	const leakGot = await tab.evaluate( ( c ) => window.leakWeights( c ), leak );
	leak.forEach( ( c, p ) => {
		const error = Math.abs( leakGot[ 4 * p ] - c.weight );
		worstLeak = Math.max( worstLeak, error );
		walled += c.weight < 1;
		++ checks;
		if ( ! ( error <= 1e-5 ) ) fail( `leak weight at ${ c.point } (map ${ c.map.size }): ${ leakGot[ 4 * p ] }, header ${ c.weight }` );
	} );
	++ checks;
	if ( errors.length ) fail( `console errors: ${ errors.join( '; ' ) }` );
} finally {
	await browser.close();
	server.close();
}
console.log( `${ bases.length } bases in WebGL; largest difference from the header ${ worst.toExponential( 2 ) } of max(1, |E|)` );
console.log( `${ adaptive.length } adaptive volumes of ${ adaptive[ 0 ].levels.length } levels through the indirection texture; largest difference ${ worstAdaptive.toExponential( 2 ) } of max(1, |E|)` );
console.log( `${ relit.length } bases relit at run time by shaders/baker_irradiance.glsl in WebGL; largest difference from the library ${ worstRelit.toExponential( 2 ) } of max(1, |E|)` );
console.log( `${ leak.length } leak-aware weights by shaders/baker_irradiance.glsl in WebGL (${ walled } below 1); largest difference from the header ${ worstLeak.toExponential( 2 ) }` );
console.log( `decoder_webgl: ${ checks - failures } of ${ checks } checks passed` );
process.exit( failures === 0 && checks > 1 && relit.length > 0 && walled > 0 ? 0 : 1 );
