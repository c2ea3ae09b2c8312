"""Worksheet 002, sections 4–6: capacity (table 4.1), static reactions by Assur groups (table
5.1) and axle loads of the tractor (table 6.1), reproduced to one unit of the last printed
digit.

Conventions (docs/worksheets.md): the program's R_i_j is the force of link i on link j.  The
worksheet's R56, R07, R23, R03, R01 follow it; its R05 is the force of link 5 on the frame
(R_5_0), its R34 the force of link 4 on link 3 (R_4_3) and its R45 the force of link 5 on link 4
(R_5_4).  GS6max is printed with a force subtracted from moments (reproduced "as printed"); the
corrected value subtracts R_amin·L.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from worksheet_tables import last_digit_unit, parse_blocks

# table 4.1; G56 is k·P·η·S_gc/I56 (the printed numbers), GS6 the capacity at S6
WS002_T41 = """
S F_act p_act Gcap_56 Gcap_S6 reserve_pct
0.420	148598	17596806	33139	27349	-0.6
0.448	138350	16383199	37094	29375	6.8
0.476	134665	15946833	39694	30178	9.7
0.503	133852	15850600	41697	30362	10.4
0.531	134603	15939567	43466	30192	9.8
0.559	136254	16135054	45232	29826	8.5
0.587	138296	16376836	47183	29386	6.9
0.614	140142	16595475	49511	28999	5.5
0.642	140956	16691883	52459	28831	4.8
0.670	139522	16522047	56377	29128	5.9
"""

# table 5.1 with the worksheet's names mapped to the program's columns
WS002_T51 = """
S Rx_5_6 Ry_5_6 Rx_0_7 Ry_0_7 Rx_2_3
0.420	39721	22161	-39721	5339	-4358
0.448	39831	28353	-39831	-853	2304
0.476	39494	34001	-39494	-6501	5903
0.503	38671	39414	-38671	-11914	7848
0.531	37275	44695	-37275	-17195	8641
0.559	35190	49836	-35190	-22336	8486
0.587	32289	54722	-32289	-27222	7445
0.614	28458	59121	-28458	-31621	5509
0.642	23655	62669	-23655	-35169	2635
0.670	17985	64891	-17985	-37391	-1195
S Ry_2_3 Rx_5_0 Ry_5_0 Rx_4_3 Ry_4_3
0.420	148534	-43972	50886	4251	-73047
0.448	138330	-44120	47212	4290	-75565
0.476	134535	-44151	44248	4656	-78249
0.503	133622	-43984	41794	5313	-81208
0.531	134326	-43558	39811	6283	-84506
0.559	135990	-42817	38326	7627	-88162
0.587	138095	-41730	37397	9440	-92118
0.614	140034	-40313	37050	11855	-96171
0.642	140932	-38682	37198	15027	-99867
0.670	139517	-37105	37480	19120	-102371
S Rx_5_4 Ry_5_4 Rx_0_3 Ry_0_3 Rx_0_1
0.420	4251	-73047	106	-75487	-4358
0.448	4290	-75565	-6594	-62765	2304
0.476	4656	-78249	-10559	-56286	5903
0.503	5313	-81208	-13161	-52414	7848
0.531	6283	-84506	-14924	-49820	8641
0.559	7627	-88162	-16112	-47827	8486
0.587	9440	-92118	-16885	-45977	7445
0.614	11855	-96171	-17364	-43863	5509
0.642	15027	-99867	-17662	-41065	2635
0.670	19120	-102371	-17925	-37146	-1195
S Ry_0_1 R_5_6 R_0_7 R_0_3 R_5_0
0.420	148534	45484	40078	75488	67252
0.448	138330	48892	39840	63110	64619
0.476	134535	52114	40026	57268	62508
0.503	133622	55217	40464	54041	60674
0.531	134326	58198	41050	52007	59010
0.559	135990	61008	41680	50469	57465
0.587	138095	63538	42233	48980	56034
0.614	140034	65613	42541	47175	54753
0.642	140932	66985	42384	44702	53665
0.670	139517	67337	41492	41245	52740
S R_4_3 R_2_3 R_5_4 R_0_1 F_act
0.420	73170	148598	73170	148598	148598
0.448	75687	138350	75687	138350	138350
0.476	78388	134665	78388	134665	134665
0.503	81382	133852	81382	133852	133852
0.531	84739	134603	84739	134603	134603
0.559	88491	136254	88491	136254	136254
0.587	92601	138296	92601	138296	138296
0.614	96899	140142	96899	140142	140142
0.642	100991	140956	100991	140956	140956
0.670	104141	139522	104141	139522	139522
"""

# table 6.1 (the worksheet prints nine rows); GS6max as printed
WS002_T61 = """
S R_front R_rear front_share_pct rear_share_pct Gmax_carrier_as_printed
0.420	21725	69775	23.7	76.3	50547
0.448	21522	69978	23.5	76.5	50001
0.476	21465	70035	23.5	76.5	49849
0.503	21528	69972	23.5	76.5	50015
0.531	21701	69799	23.7	76.3	50483
0.559	21987	69513	24.0	76.0	51272
0.587	22391	69109	24.5	75.5	52430
0.614	22922	68578	25.1	74.9	54035
0.642	23593	67907	25.8	74.2	56210
"""


@pytest.fixture(scope="module")
def frc(ws002):
    return ws002.forces


def _check(table, text):
    n = 0
    for header, rows in parse_blocks(text):
        for r in rows:
            S = float(r[0])
            i = int(np.argmin(np.abs(table.q.to_numpy() - S)))
            assert abs(table.q.iloc[i] - S) < 1e-3
            for col, printed in zip(header[1:], r[1:]):
                got = float(table[col].iloc[i])
                unit = last_digit_unit(printed)
                assert abs(got - float(printed)) <= unit * (1 + 1e-9), f"S={S} {col}: {got} vs {printed}"
                n += 1
    return n


def test_table_4_1_capacity(frc):
    assert _check(frc.table, WS002_T41) == 50


def test_table_5_1_reactions(frc):
    assert _check(frc.table, WS002_T51) == 250


def test_table_6_1_axle_loads(frc):
    assert _check(frc.table, WS002_T61) == 45


def test_pressure_exceeds_the_system_pressure_at_the_lowest_position(frc):
    """At S = 0.420 the required pressure exceeds p_max (reserve −0,6 %): a finding."""
    t, sc = frc.table, frc.scalars
    assert sc["pressure_exceeded"]
    assert t.p_act.iloc[0] > 17.5e6 > t.p_act.iloc[1:].max()
    assert t.reserve_pct.iloc[0] < 0 < t.reserve_pct.iloc[1:].min()
    assert math.isclose(sc["F_cyl_max"], 2 * 17.5e6 * 0.84 * math.pi * 0.08 ** 2 / 4, rel_tol=1e-15)


def test_static_force_is_load_times_transfer_ratio(frc, ws002):
    """F_gc = P6·IS6 (virtual work) and the capacities are F_max/I."""
    t = frc.table
    k = ws002.kinematics
    assert np.allclose(t.F_act, 27500 * k.IS6, rtol=1e-13, atol=0)
    assert np.allclose(t.Gcap_56, frc.scalars["F_cyl_max"] / k.I56, rtol=1e-13, atol=0)
    assert np.allclose(t.Gcap_S6, frc.scalars["F_cyl_max"] / k.IS6, rtol=1e-13, atol=0)
    # the Жуковский lever and the power balance agree with the group-by-group solution
    assert t.dev_zhukovsky_pct.max() < 1e-10
    assert t.dev_power.max() < 1e-12
    # cylinder and rod are massless: the driving pair carries only the axial force
    assert np.abs(t.N_1_2).max() < 1e-9 * t.F_act.max()
    assert np.allclose(t.R_0_1, t.F_act, rtol=1e-13) and np.allclose(t.R_2_3, t.F_act, rtol=1e-13)


def test_carrier_maximum_capacity_corrected(frc):
    """GS6max as printed subtracts R_amin (a force) from moments; the corrected value
    subtracts R_amin·L, and the self-consistent one makes R_A equal its minimum exactly."""
    t = frc.table
    Ramin = 0.2 * (27500 + 56000 + 8000)
    m0 = 8000 * (0.6 + 2.96) + 56000 * 1.62
    assert np.array_equal(t.x_load, frc.solution.cols["x_S6"])     # rear axle at x = 0
    assert np.allclose(t.Gmax_carrier_as_printed, (m0 - Ramin) / t.x_load, rtol=1e-14)
    assert np.allclose(t.Gmax_carrier, (m0 - Ramin * 2.96) / t.x_load, rtol=1e-14)
    G = t.Gmax_carrier_consistent.to_numpy()
    RA = (m0 - G * t.x_load.to_numpy()) / 2.96
    assert np.allclose(RA, 0.2 * (G + 56000 + 8000), rtol=1e-13)
    # with the nominal load the steered axle keeps more than 20 % of the weight everywhere
    assert (t.front_share_pct > 20).all()
    assert np.allclose(t.R_front + t.R_rear, 91500, rtol=1e-15)
