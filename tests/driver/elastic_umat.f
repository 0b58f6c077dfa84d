C     A third-party-style Abaqus UMAT, written for ecm's tests of ecm-point --umat (not ecm's):
C     isotropic linear elasticity in Abaqus's own layout and conventions.
C       PROPS(1) E (MPa), PROPS(2) nu, PROPS(3) the largest strain increment component it
C       accepts (0: any; above it the call asks for a smaller increment, PNEWDT = 0.5, and
C       leaves everything as it came).
C       STATEV(1) counts the calls with a non-zero increment (NSTATV >= 1).
      SUBROUTINE UMAT(STRESS,STATEV,DDSDDE,SSE,SPD,SCD,
     1 RPL,DDSDDT,DRPLDE,DRPLDT,
     2 STRAN,DSTRAN,TIME,DTIME,TEMP,DTEMP,PREDEF,DPRED,CMNAME,
     3 NDI,NSHR,NTENS,NSTATV,PROPS,NPROPS,COORDS,DROT,PNEWDT,
     4 CELENT,DFGRD0,DFGRD1,NOEL,NPT,LAYER,KSPT,KSTEP,KINC)
      IMPLICIT NONE
      CHARACTER*80 CMNAME
      INTEGER NDI,NSHR,NTENS,NSTATV,NPROPS,NOEL,NPT,LAYER,KSPT,KINC
      INTEGER KSTEP(4)
      DOUBLE PRECISION STRESS(NTENS),STATEV(NSTATV),
     1 DDSDDE(NTENS,NTENS),DDSDDT(NTENS),DRPLDE(NTENS),
     2 STRAN(NTENS),DSTRAN(NTENS),TIME(2),PREDEF(1),DPRED(1),
     3 PROPS(NPROPS),COORDS(3),DROT(3,3),DFGRD0(3,3),DFGRD1(3,3)
      DOUBLE PRECISION SSE,SPD,SCD,RPL,DRPLDT,DTIME,TEMP,DTEMP,
     1 PNEWDT,CELENT
      DOUBLE PRECISION E,ANU,DMAX,ALAMB,AMU
      INTEGER I,J
      LOGICAL MOVED
      E = PROPS(1)
      ANU = PROPS(2)
      DMAX = PROPS(3)
      MOVED = .FALSE.
      DO I = 1, NTENS
        IF (DMAX .GT. 0.D0 .AND. ABS(DSTRAN(I)) .GT. DMAX) THEN
          PNEWDT = 0.5D0
          RETURN
        END IF
        IF (DSTRAN(I) .NE. 0.D0) MOVED = .TRUE.
      END DO
      ALAMB = E*ANU/((1.D0+ANU)*(1.D0-2.D0*ANU))
      AMU = E/(2.D0*(1.D0+ANU))
      DO J = 1, NTENS
        DO I = 1, NTENS
          DDSDDE(I,J) = 0.D0
        END DO
      END DO
      DO I = 1, NDI
        DO J = 1, NDI
          DDSDDE(I,J) = ALAMB
        END DO
        DDSDDE(I,I) = ALAMB + 2.D0*AMU
      END DO
      DO I = NDI+1, NTENS
        DDSDDE(I,I) = AMU
      END DO
      SSE = 0.D0
      DO I = 1, NTENS
        DO J = 1, NTENS
          STRESS(I) = STRESS(I) + DDSDDE(I,J)*DSTRAN(J)
        END DO
      END DO
      DO I = 1, NTENS
        SSE = SSE + 0.5D0*STRESS(I)*(STRAN(I)+DSTRAN(I))
      END DO
      IF (MOVED) STATEV(1) = STATEV(1) + 1.D0
      RETURN
      END
