// `baker view` end to end: a page written for the bundled room (ad-ycocg, the scene found beside
// the volume) opened in Debian's headless Chromium (SwiftShader WebGL 2). The colour at three
// probes' sphere centres, after undoing the page's display transform (sRGB of E/π · exposure),
// must be baker sample's irradiance at that probe for the normal facing the camera within 2 %;
// the probe-state toggle must recolour a relocated probe; a click prints baker sample's six
// axis values; no console error. --serve serves the same files. A damaged volume writes no page.
// A screenshot of the page is saved to SCREENSHOT when given.
// argv: node viewer.test.mjs BAKER SOURCE_DIR [SCREENSHOT]
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { bake, baker, check, finish, freshDirectory, runBaker, sample, sourceDir } from './support.mjs';
import { openPage, serve } from './browser.mjs';

const screenshot = process.argv[ 4 ] && path.resolve( process.argv[ 4 ] );
const dir = freshDirectory( 'viewer' );
for ( const file of [ 'default_room.gltf', 'default_room.bin' ] ) fs.copyFileSync( path.join( sourceDir, 'data/default_room', file ), path.join( dir, file ) );
bake( [ 'default_room.gltf', '--basis', 'ad-ycocg', '--rays', '256', '--spacing', '1', '--seed', '1', '--out', 'room.vdb' ], dir );
const written = runBaker( [ 'view', 'room.vdb', '--out', 'page', '--json' ], dir );
check( written.code === 0, `baker view: exit ${ written.code }, ${ written.stderr }` );
const summary = JSON.parse( written.stdout || '{}' );
check( summary.scene && summary.scene.endsWith( 'default_room.gltf' ), `the scene beside the volume is found: ${ summary.scene }` );

function srgbToLinear( byte ) {
	const v = byte / 255;
	return v <= 0.04045 ? v / 12.92 : Math.pow( ( v + 0.055 ) / 1.055, 2.4 );
}

const { server, url } = await serve( null, { '/': path.join( dir, 'page' ) } );
const { browser, page, errors } = await openPage( url, { width: 1024, height: 640 } );
try {
	await page.waitForFunction( 'window.viewerReady === true || document.getElementById( "summary" ).textContent.startsWith( "cannot" )', { timeout: 90000 } ).catch( () => {} );
	check( await page.evaluate( () => window.viewerReady === true ), `the page is ready (errors: ${ errors.join( '; ' ) })` );
	const info = await page.evaluate( () => window.viewer.info );
	const [ nx, ny, nz ] = info.dims;
	const states = await page.evaluate( () => fetch( 'volume.bin' ).then( ( r ) => r.arrayBuffer() ).then( ( b ) => Array.from( new Int32Array( b ) ) ) );
	const stateOf = ( [ i, j, k ] ) => states[ info.binary.sections.states.byte_offset / 4 + i + nx * ( j + ny * k ) ];
	// Three valid probes, each seen from its own side, at an exposure that shows its brightest
	// channel at 0.8 (8-bit sRGB steps stay well under 1 % there).
	const valid = [];
	for ( let k = 1; k < nz; ++ k ) for ( let j = 1; j < ny; ++ j ) for ( let i = 1; i < nx; ++ i ) if ( stateOf( [ i, j, k ] ) === 1 ) valid.push( [ i, j, k ] );
	const probes = [ valid[ 0 ], valid[ Math.floor( valid.length / 2 ) ], valid[ valid.length - 1 ] ];
	const views = [ [ 0.3, 0.4, 1 ], [ - 0.5, 0.2, 0.8 ], [ 0.6, - 0.3, 0.7 ] ];
	check( valid.length >= 3, `three valid probes to look at: ${ JSON.stringify( valid ) }` );
	for ( const [ n, ijk ] of probes.entries() ) {
		const length = Math.hypot( ...views[ n ] ), normal = views[ n ].map( ( v ) => v / length );
		const position = ijk.map( ( i, a ) => info.origin[ a ] + info.spacing * i );
		const expected = sample( path.join( dir, 'room.vdb' ), position, normal ).irradiance;
		const brightest = Math.max( ...expected );
		await page.evaluate( ( stops ) => window.viewer.setOption( 'exposure', stops ), Math.log2( 0.8 * Math.PI / brightest ) );
		const shot = await page.evaluate( ( ijk, towards ) => window.viewer.captureProbe( ijk, towards ), ijk, views[ n ] );
		const rendered = [ 0, 1, 2 ].map( ( c ) => shot.pixels.reduce( ( sum, p ) => sum + srgbToLinear( p[ c ] ), 0 ) / 4 * Math.PI / shot.exposure );
		for ( let c = 0; c < 3; ++ c ) {
			check( Math.abs( rendered[ c ] - expected[ c ] ) <= 0.02 * brightest,
				`probe ${ ijk } channel ${ c }: rendered ${ rendered[ c ].toFixed( 5 ) } (pixels ${ JSON.stringify( shot.pixels ) }), baker sample ${ expected[ c ].toFixed( 5 ) }` );
		}
		console.log( `probe ${ ijk } seen along (${ shot.normal.map( ( v ) => v.toFixed( 3 ) ) }): page E = (${ rendered.map( ( v ) => v.toFixed( 4 ) ) }), baker sample E = (${ expected.map( ( v ) => v.toFixed( 4 ) ) }); largest difference ${ ( 100 * Math.max( ...rendered.map( ( r, c ) => Math.abs( r - expected[ c ] ) ) ) / brightest ).toFixed( 2 ) } % of the brightest channel` );
	}
	await page.evaluate( () => window.viewer.setOption( 'exposure', 0 ) );

	// A relocated probe turns the state colour (yellow) when the toggle is on.
	const relocated = [];
	for ( let k = 0; k < nz; ++ k ) for ( let j = 0; j < ny; ++ j ) for ( let i = 0; i < nx; ++ i ) if ( stateOf( [ i, j, k ] ) === 2 ) relocated.push( [ i, j, k ] );
	check( relocated.length > 0, 'the room has a relocated probe' );
	if ( relocated.length ) {
		const before = await page.evaluate( ( ijk ) => window.viewer.captureProbe( ijk, [ 0, 0, 1 ] ), relocated[ 0 ] );
		await page.evaluate( () => window.viewer.setOption( 'show-states', true ) );
		const after = await page.evaluate( ( ijk ) => window.viewer.captureProbe( ijk, [ 0, 0, 1 ] ), relocated[ 0 ] );
		await page.evaluate( () => window.viewer.setOption( 'show-states', false ) );
		const [ b, a ] = [ before.pixels[ 0 ], after.pixels[ 0 ] ];
		check( a.join() !== b.join() && Math.abs( a[ 0 ] - 0xfb ) <= 2 && Math.abs( a[ 1 ] - 0xbc ) <= 2 && a[ 2 ] <= 8,
			`relocated probe ${ relocated[ 0 ] }: ${ b } with irradiance, ${ a } with states` );
	}

	// A click's six axis values are baker sample's at the same point.
	const point = [ 0.25, 1.2, 1.7 ];
	const picked = await page.evaluate( ( p ) => window.viewer.pick( p ), point );
	for ( const [ name, e ] of Object.entries( picked.irradiance ) ) {
		const axis = { X: 0, Y: 1, Z: 2 }[ name[ 1 ] ], normal = [ 0, 0, 0 ];
		normal[ axis ] = name[ 0 ] === '-' ? - 1 : 1;
		const expected = sample( path.join( dir, 'room.vdb' ), point, normal ).irradiance;
		check( e.every( ( v, c ) => Math.abs( v - expected[ c ] ) <= 1e-5 * Math.max( 1, Math.abs( expected[ c ] ) ) ), `pick ${ name }: ${ e } against ${ expected }` );
	}

	// A real click on the canvas (the default view's centre looks at the room) prints a point.
	await page.mouse.click( 700, 330 );
	const printed = await page.evaluate( () => document.getElementById( 'picked' ).textContent );
	check( /^position \(/.test( printed ) && /\+X {2}E = \(/.test( printed ) && /-Z {2}E = \(/.test( printed ), `a click prints the point and six axes: ${ printed }` );

	if ( screenshot ) {
		fs.mkdirSync( path.dirname( screenshot ), { recursive: true } );
		await page.evaluate( () => window.viewer.resetExposure() );
		await page.screenshot( { path: screenshot } );
		console.log( `screenshot: ${ screenshot }` );
	}
	check( errors.length === 0, `console errors: ${ errors.join( '; ' ) }` );
} finally {
	await browser.close();
	server.close();
}

// --serve: the same files from baker itself, on a free port it prints.
const served = spawn( baker, [ 'view', 'room.vdb', '--out', 'page', '--serve', '0' ], { cwd: dir } );
const address = await new Promise( ( resolve ) => {
	let out = '';
	served.stdout.on( 'data', ( d ) => { out += d; const m = out.match( /http:\/\/127\.0\.0\.1:\d+\// ); if ( m ) resolve( m[ 0 ] ); } );
	setTimeout( () => resolve( null ), 30000 );
} );
check( address !== null, 'baker view --serve prints its address' );
if ( address ) {
	const index = await fetch( address );
	const json = await fetch( address + 'volume.json' ).then( ( r ) => r.json() );
	const outside = await fetch( address + '..%2f..%2froom.vdb' );
	check( index.ok && ( await index.text() ).includes( 'viewer.js' ) && json.basis === 'ad-ycocg' && outside.status === 404, `served ${ index.status }, ${ json.basis }, outside ${ outside.status }` );
}
served.kill();

// A damaged volume: the reader's message, exit 2, no page.
fs.writeFileSync( path.join( dir, 'damaged.vdb' ), fs.readFileSync( path.join( dir, 'room.vdb' ) ).subarray( 0, 400 ) );
const damaged = runBaker( [ 'view', 'damaged.vdb', '--out', 'damaged_page' ], dir );
check( damaged.code === 2 && damaged.stderr.includes( 'damaged.vdb' ) && ! fs.existsSync( path.join( dir, 'damaged_page' ) ), `damaged volume: exit ${ damaged.code }, ${ damaged.stderr.trim() }` );
const foreign = runBaker( [ 'view', 'page', '--out', 'foreign_page' ], dir );
check( foreign.code === 2 && ! fs.existsSync( path.join( dir, 'foreign_page' ) ), `a directory that is no volume: exit ${ foreign.code }, ${ foreign.stderr.trim() }` );
finish( 'viewer' );
