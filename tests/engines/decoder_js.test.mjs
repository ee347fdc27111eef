// decoders/baker_irradiance.js against decoders/baker_irradiance.h: for every basis, the
// irradiance and visibility the header decodes from random coefficients (decoder_samples) agree
// within 1e-5 of the coefficients' magnitude (≤ 1). Then adaptive volumes (decoder_samples
// adaptive): finestLevelNeighbourhood picks the header's level and weights at every point, and E
// and visibility blended there agree within 1e-5 of max(1, |E|). Then radiance volumes
// (decoder_samples radiance): radiance, irradiance, visibility and specular against the library's
// readings within 1e-5 of max(1, |value|), and the piecewise Ambient Dice variants refused. Then
// relighting at run time (decoder_samples relit): relitIrradiance against the library's within
// 1e-5 of max(1, |E|), every basis. Then leak-aware weights (decoder_samples leak): leakWeight
// against the header's within 1e-12, open and walled maps alike.
// argv: node decoder_js.test.mjs DECODER_SAMPLES SOURCE_DIR
import { execFileSync } from 'node:child_process';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const [ samplesBinary, sourceDir ] = process.argv.slice( 2 );
const { BasisDecoder, blendProbes, finestLevelNeighbourhood, leakWeight } = await import( pathToFileURL( path.join( sourceDir, 'decoders/baker_irradiance.js' ) ) );
const samples = ( ...args ) => JSON.parse( execFileSync( samplesBinary, args, { encoding: 'utf8', maxBuffer: 1 << 30 } ) );
const bases = samples(), adaptive = samples( 'adaptive' ), radiance = samples( 'radiance' ), relit = samples( 'relit' ), leak = samples( 'leak' );
let checks = 0, failures = 0, worst = 0;
for ( const entry of bases ) {
	const decoder = new BasisDecoder( entry.basis, entry.sharpness ?? 0 );
	if ( entry.axes ) decoder.setLobeAxes( entry.axes );
	++ checks;
	if ( ! decoder.valid || decoder.coefficientsPerProbe !== entry.coefficients_per_probe ) {
		++ failures;
		console.error( `FAIL: ${ entry.basis }: valid ${ decoder.valid }, ${ decoder.coefficientsPerProbe } coefficients per probe` );
		continue;
	}
	for ( const c of entry.cases ) {
		const got = [ ...decoder.irradiance( c.coefficients, c.direction ), decoder.visibility( c.coefficients, c.direction ) ];
		const expected = [ ...c.irradiance, c.visibility ];
		for ( let k = 0; k < 4; ++ k ) {
			const error = Math.abs( got[ k ] - expected[ k ] );
			worst = Math.max( worst, error );
			++ checks;
			if ( ! ( error <= 1e-5 ) ) {
				if ( ++ failures <= 20 ) console.error( `FAIL: ${ entry.basis } at ${ c.direction }: value ${ k } ${ got[ k ] }, header ${ expected[ k ] }` );
			}
		}
	}
}
// Level l's probes as a level-wide array, as probeNeighbourhood numbers them (zeros where not held).
function levelProbes( level, key, count ) {
	const [ nx, ny, nz ] = level.dims, bx = Math.ceil( nx / 8 ), by = Math.ceil( ny / 8 );
	const out = new Float64Array( nx * ny * nz * count );
	level.bricks.forEach( ( b, s ) => {
		const x0 = 8 * ( b % bx ), y0 = 8 * ( Math.floor( b / bx ) % by ), z0 = 8 * Math.floor( b / ( bx * by ) );
		for ( let k = 0; k < 8; ++ k ) for ( let j = 0; j < 8; ++ j ) for ( let i = 0; i < 8; ++ i ) {
			if ( x0 + i >= nx || y0 + j >= ny || z0 + k >= nz ) continue;
			const from = ( 512 * s + i + 8 * ( j + 8 * k ) ) * count, to = ( x0 + i + nx * ( y0 + j + ny * ( z0 + k ) ) ) * count;
			out.set( level[ key ].slice( from, from + count ), to );
		}
	} );
	return out;
}
let worstAdaptive = 0;
for ( const entry of adaptive ) {
	const decoder = new BasisDecoder( entry.basis, 0 );
	const perProbe = decoder.coefficientsPerProbe, count0 = decoder.coefficientCount( 0 );
	const levels = entry.levels.map( ( l ) => {
		const subBricksHeld = new Uint8Array( l.dims.reduce( ( n, d ) => n * Math.ceil( d / 8 ), 1 ) );
		l.bricks.forEach( ( b, s ) => { subBricksHeld[ b ] = l.masks[ s ]; } );
		return { ...l, subBricksHeld, values: levelProbes( l, 'coefficients', perProbe ), visibilityValues: levelProbes( l, 'visibility', count0 ) };
	} );
	for ( const point of entry.points ) {
		const picked = finestLevelNeighbourhood( point.position, levels );
		const level = levels[ picked.level ];
		++ checks;
		if ( picked.level !== point.level || picked.weight.some( ( w, c ) => Math.abs( w - point.weights[ c ] ) > 1e-12 ) ) {
			if ( ++ failures <= 20 ) console.error( `FAIL: adaptive ${ entry.basis } at ${ point.position }: level ${ picked.level } weights ${ picked.weight }, header level ${ point.level } weights ${ point.weights }` );
			continue;
		}
		const got = [ ...decoder.irradiance( blendProbes( level.values, picked, perProbe ), point.normal ),
			decoder.visibility( blendProbes( level.visibilityValues, picked, count0 ), point.normal ) ];
		const expected = [ ...point.irradiance, point.visibility ];
		for ( let k = 0; k < 4; ++ k ) {
			const error = Math.abs( got[ k ] - expected[ k ] ) / Math.max( 1, Math.abs( expected[ k ] ) );
			worstAdaptive = Math.max( worstAdaptive, error );
			++ checks;
			if ( ! ( error <= 1e-5 ) && ++ failures <= 20 ) console.error( `FAIL: adaptive ${ entry.basis } at ${ point.position }: value ${ k } ${ got[ k ] }, header ${ expected[ k ] }` );
		}
	}
}
console.log( `${ adaptive.length } adaptive volumes: the header's level and weights at every point; largest difference in E ${ worstAdaptive.toExponential( 2 ) } of max(1, |E|)` );
let worstRadiance = 0, decodedRadiance = 0;
for ( const entry of radiance ) {
	const decoder = new BasisDecoder( entry.basis, entry.sharpness ?? 0 );
	if ( entry.axes ) decoder.setLobeAxes( entry.axes );
	if ( entry.diffuse_response?.type === 'legendre' ) decoder.setDiffuseResponse( entry.diffuse_response.coefficients );
	++ checks;
	if ( decoder.decodesRadiance !== ( entry.diffuse_response !== null ) ) {
		++ failures;
		console.error( `FAIL: radiance ${ entry.basis }: decodesRadiance ${ decoder.decodesRadiance }, the file's response ${ JSON.stringify( entry.diffuse_response ) }` );
		continue;
	}
	if ( ! decoder.decodesRadiance ) continue;
	++ decodedRadiance;
	for ( const c of entry.cases ) {
		const s = decoder.specular( c.coefficients, c.normal, c.view, c.roughness, entry.specular );
		const got = [ ...decoder.radiance( c.coefficients, c.normal ), ...decoder.irradianceFromRadiance( c.coefficients, c.normal ),
			decoder.visibilityFromRadiance( c.coefficients, c.normal ), ...s.value, s.albedo, s.diffuseWeight ];
		const expected = [ ...c.radiance, ...c.irradiance, c.visibility, ...c.specular.value, c.specular.albedo, c.specular.diffuse_weight ];
		for ( let k = 0; k < got.length; ++ k ) {
			const error = Math.abs( got[ k ] - expected[ k ] ) / Math.max( 1, Math.abs( expected[ k ] ) );
			worstRadiance = Math.max( worstRadiance, error );
			++ checks;
			if ( ! ( error <= 1e-5 ) && ++ failures <= 20 ) console.error( `FAIL: radiance ${ entry.basis } at ${ c.normal }: value ${ k } ${ got[ k ] }, library ${ expected[ k ] }` );
		}
	}
}
console.log( `${ decodedRadiance } of ${ radiance.length } bases decode radiance; largest difference from the library ${ worstRadiance.toExponential( 2 ) } of max(1, |value|)` );
let worstRelit = 0;
for ( const entry of relit ) {
	const decoder = new BasisDecoder( entry.basis, entry.sharpness ?? 0 );
	if ( entry.axes ) decoder.setLobeAxes( entry.axes );
	for ( const c of entry.cases ) {
		const got = decoder.relitIrradiance( c.rest, c.visibility, c.normal, c.sky );
		for ( let k = 0; k < 3; ++ k ) {
			const error = Math.abs( got[ k ] - c.irradiance[ k ] ) / Math.max( 1, Math.abs( c.irradiance[ k ] ) );
			worstRelit = Math.max( worstRelit, error );
			++ checks;
			if ( ! ( error <= 1e-5 ) && ++ failures <= 20 ) console.error( `FAIL: relit ${ entry.basis } at ${ c.normal }: ${ got[ k ] }, library ${ c.irradiance[ k ] }` );
		}
	}
}
console.log( `${ relit.length } bases relit at run time; largest difference from the library ${ worstRelit.toExponential( 2 ) } of max(1, |E|)` );
let worstLeak = 0, walled = 0;
for ( const c of leak ) {
	const got = leakWeight( c.map, c.moments, c.probe, c.point, c.normal, 1 );
	const error = Math.abs( got - c.weight );
	worstLeak = Math.max( worstLeak, error );
	if ( c.weight < 1 ) ++ walled;
	++ checks;
	if ( ! ( error <= 1e-12 ) && ++ failures <= 20 ) console.error( `FAIL: leak weight at ${ c.point }: ${ got }, header ${ c.weight }` );
}
console.log( `${ leak.length } leak-aware weights (${ walled } below 1); largest difference from the header ${ worstLeak.toExponential( 2 ) }` );
console.log( `${ bases.length } bases; largest difference from the header ${ worst.toExponential( 2 ) }` );
console.log( `decoder_js: ${ checks - failures } of ${ checks } checks passed` );
process.exit( failures === 0 && bases.length > 0 && decodedRadiance > 0 && relit.length > 0 && walled > 0 ? 0 : 1 );
